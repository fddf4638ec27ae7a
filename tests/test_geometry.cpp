// host/geometry: mesh files through Assimp, the scene flattened into world space, the BVH's
// invariants on ordinary and degenerate inputs, and the device layout's conservative rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>

#include <sys/stat.h>

#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "geometry/bvh.h"
#include "geometry/device_geometry.h"
#include "geometry/mesh_file.h"
#include "geometry/scene_bvh.h"
#include "geometry/scene_shapes.h"
#include "peers/knot_mesh.h"
#include "scene/scene.h"
#include "scene/transform.h"
#include "input_error_of.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using testing::input_error_of;
using testing::TempDir;

void write_text(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(MeshFile, BinaryPlyRoundTrips) {
  TempDir dir;
  const TriangleMesh knot = trefoil_knot(40, 8);
  write_ply(dir / "knot.ply", knot);
  const TriangleMesh read = read_mesh(dir / "knot.ply");
  ASSERT_EQ(read.triangles.size(), knot.triangles.size());
  // Assimp may split vertices per face, so compare the triangles' corners, not the index lists.
  for (std::size_t t = 0; t < knot.triangles.size(); t += 37)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(read.vertices[read.triangles[t][k]], knot.vertices[knot.triangles[t][k]]) << "triangle " << t;
}

// Assimp 5.2 misreads a binary PLY whose data starts with the byte '\n' (assimp/assimp#5341):
// read_mesh hands such a file over with a CRLF header. A first vertex x of 0x3f80000a starts the
// data with that byte (little-endian), 1.0f with a zero.
TEST(MeshFile, BinaryPlyWhoseDataStartsWithANewlineIsReadRight) {
  TempDir dir;
  for (std::uint32_t bits : {0x3f80000au, 0x3f800000u}) {
    TriangleMesh mesh = trefoil_knot(12, 5);
    std::memcpy(&mesh.vertices[0].x, &bits, sizeof bits);
    write_ply(dir / "first.ply", mesh);
    const TriangleMesh read = read_mesh(dir / "first.ply");
    ASSERT_EQ(read.triangles.size(), mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(read.vertices[read.triangles[t][k]], mesh.vertices[mesh.triangles[t][k]]) << std::hex << bits;
  }
}

TEST(MeshFile, ObjPolygonsAreTriangulatedAndPointsDropped) {
  TempDir dir;
  write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3 4\np 5\n");
  const TriangleMesh quad = read_mesh(dir / "quad.obj");
  EXPECT_EQ(quad.triangles.size(), 2u);
}

TEST(MeshFile, BadFilesAreOneLineErrorsNamingTheFile) {
  TempDir dir;
  const std::string missing = input_error_of([&] { read_mesh(dir / "missing.ply"); });
  EXPECT_NE(missing.find("missing.ply"), std::string::npos) << missing;

  write_text(dir / "garbage.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 99999999\nproperty float x\nend_header\nxx");
  const std::string garbage = input_error_of([&] { read_mesh(dir / "garbage.ply"); });
  EXPECT_NE(garbage.find("garbage.ply"), std::string::npos) << garbage;
  EXPECT_EQ(garbage.find('\n'), std::string::npos) << garbage;

  // A header that declares two billion vertices in a few bytes is refused before anything is read.
  write_text(dir / "huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 2000000000\n"
                               "property list uchar int vertex_indices\nend_header\n0123456789");
  const std::string huge = input_error_of([&] { read_mesh(dir / "huge.ply"); });
  EXPECT_NE(huge.find("huge.ply: its header declares elements that need at least 26000000000 bytes"), std::string::npos) << huge;
  // A file cut short.
  write_ply(dir / "knot.ply", trefoil_knot(10, 4));
  std::ifstream whole(dir / "knot.ply", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.ply", std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "cut.ply"); }).find("cut.ply"), std::string::npos);

  write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\np 1\np 2\n");
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "points.obj"); }).find("points.obj"), std::string::npos);

  TriangleMesh broken = trefoil_knot(3, 3);
  broken.vertices[4].y = std::numeric_limits<float>::quiet_NaN();
  write_ply(dir / "nan.ply", broken);
  const std::string nan = input_error_of([&] { read_mesh(dir / "nan.ply"); });
  EXPECT_NE(nan.find("nan.ply"), std::string::npos) << nan;
  EXPECT_NE(nan.find("not finite"), std::string::npos) << nan;
}

// A triangle's PLY header: three vertices and `faces` faces, each a uchar-counted list of ints.
std::string triangle_header(const std::string& format, int faces) {
  return "ply\nformat " + format + " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" +
         "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string binary_triangle(std::uint8_t corners) {
  std::string bytes = triangle_header("binary_little_endian", 1);
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bytes.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  bytes.push_back(static_cast<char>(corners));
  const std::int32_t indices[3] = {0, 1, 2};
  bytes.append(reinterpret_cast<const char*>(indices), std::min<std::size_t>(sizeof indices, 4u * corners));
  return bytes;
}

// Assimp 5.2 aborts the process on a face without corners (an assert in its triangulation).
TEST(MeshFile, AFaceWithNoCornersIsAnError) {
  TempDir dir;
  write_text(dir / "ascii.ply", triangle_header("ascii", 2) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n");
  std::ofstream(dir / "binary.ply", std::ios::binary) << binary_triangle(0);
  for (const char* name : {"ascii.ply", "binary.ply"}) {
    const std::string error = input_error_of([&] { read_mesh(dir / name); });
    EXPECT_NE(error.find(std::string(name) + ": face "), std::string::npos) << error;
    EXPECT_NE(error.find("with no corners"), std::string::npos) << error;
  }
  std::ofstream(dir / "good.ply", std::ios::binary) << binary_triangle(3);
  EXPECT_EQ(read_mesh(dir / "good.ply").triangles.size(), 1u);
}

// Assimp 5.2 spins for ever on a PLY header cut short: every cut inside the header is an error.
TEST(MeshFile, AHeaderCutAnywhereIsAnError) {
  TempDir dir;
  const std::string header = triangle_header("ascii", 1);
  for (std::size_t cut = 4; cut < header.size(); cut += 7) {
    write_text(dir / "cut.ply", header.substr(0, cut));
    const std::string error = input_error_of([&] { read_mesh(dir / "cut.ply"); });
    EXPECT_NE(error.find("cut.ply: "), std::string::npos) << "cut at " << cut << ": " << error;
  }
  write_text(dir / "cut.ply", header.substr(0, header.size() - 3));
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "cut.ply"); }).find("ends before end_header"), std::string::npos);
}

// Assimp allocates a list's claimed length before reading it: 4 billion corners in a few bytes is
// 16 GB. Every list is held to the bytes after it, and the header's counts to the file's size
// however long the header is.
TEST(MeshFile, ClaimedCountsAreHeldToTheFilesSize) {
  TempDir dir;
  std::string bytes = triangle_header("binary_little_endian", 1);
  bytes = bytes.replace(bytes.find("uchar int"), 9, "uint int");
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bytes.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const std::uint32_t corners = 0xfffffff0u;
  bytes.append(reinterpret_cast<const char*>(&corners), sizeof corners);
  bytes.append(12, '\0');
  std::ofstream(dir / "list.ply", std::ios::binary) << bytes;
  const std::string list = input_error_of([&] { read_mesh(dir / "list.ply"); });
  EXPECT_NE(list.find("list.ply: face 0 of 1: a list of 4294967280 vertex_indices runs past the end"), std::string::npos)
      << list;
  // In ASCII: 188 bytes that took 9 GB before failing.
  std::string ascii = triangle_header("ascii", 1);
  write_text(dir / "ascii.ply", ascii.replace(ascii.find("uchar int"), 9, "uint int") + "0 0 0\n1 0 0\n0 1 0\n1999999999 0 1 2\n");
  const std::string ascii_list = input_error_of([&] { read_mesh(dir / "ascii.ply"); });
  EXPECT_NE(ascii_list.find("ascii.ply: face 0 of 1: a list of 1999999999 vertex_indices runs past the end"),
            std::string::npos)
      << ascii_list;

  std::string padded = triangle_header("ascii", 200000000);
  padded.insert(padded.find("element vertex"), std::string(70000, 'c').replace(0, 8, "comment ") + "\n");
  write_text(dir / "padded.ply", padded + "0 0 0\n");
  const std::string claimed = input_error_of([&] { read_mesh(dir / "padded.ply"); });
  EXPECT_NE(claimed.find("padded.ply: its header declares elements that need at least"), std::string::npos) << claimed;
}

TEST(MeshFile, MalformedHeadersSayWhatIsWrong) {
  TempDir dir;
  const std::string header = triangle_header("ascii", 1), data = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto error_with = [&](const std::string& from, const std::string& to) {
    std::string text = header + data;
    text.replace(text.find(from), from.size(), to);
    write_text(dir / "bad.ply", text);
    return input_error_of([&] { read_mesh(dir / "bad.ply"); });
  };
  EXPECT_NE(error_with("face 1", "face -10").find("has count '-10', not a whole number >= 0"), std::string::npos);
  EXPECT_NE(error_with("float z", "float w").find("no vertex element with x, y and z"), std::string::npos);
  EXPECT_NE(error_with("float y", "quaternion y").find("'quaternion' is not a PLY type"), std::string::npos);
  // A vertex of z, y, z and no x (the fuzzer's): Assimp read a float as a face's corner count, 8.5 GB.
  EXPECT_NE(error_with("float x", "float z").find("property 'z' of element 'vertex' is declared twice"),
            std::string::npos);
  // A second vertex element (the fuzzer's): Assimp freed memory it had not allocated.
  EXPECT_NE(error_with("element face", "element vertex").find("element 'vertex' is declared twice"),
            std::string::npos);
  EXPECT_NE(error_with("ascii", "utf8").find("header line 2: must be 'format ascii 1.0'"), std::string::npos);
  EXPECT_NE(error_with("3 0 1 2", "3 0 one 2").find("'one' is not an integer"), std::string::npos);
  // Assimp reads an ASCII record from a line of its own (it aborted on a face on a vertex's line).
  EXPECT_NE(error_with("0 1 0\n3", "0 1 0 3").find("vertex 2 of 3: its line holds more values"), std::string::npos);
  EXPECT_NE(error_with("0 1 0\n", "0 1\n0\n").find("its line ends before its values do"), std::string::npos);
  // Assimp neither stops nor moves on past 19 digits: the values after were read from the wrong place.
  EXPECT_NE(error_with("0 1 0\n", "0" + std::string(30, '5') + " 1 0\n").find("has more than 18 digits in a row"),
            std::string::npos);
  // Assimp ends a word at a NUL: this face list was vertex_indices to it, with a face of no corners.
  EXPECT_NE(error_with("vertex_indices", std::string("vertex_indices\0at", 17)).find("not printable text (0)"),
            std::string::npos);
}

// Assimp's PLY reader takes any file named .ply, and a file of an unknown extension by "ply" in
// its first bytes (it crashed on "plyply\n..."): each is checked as PLY or refused.
TEST(MeshFile, EveryFileThePlyReaderCouldTakeIsCheckedFirst) {
  TempDir dir;
  write_text(dir / "twice.ply", "plyply\n" + triangle_header("ascii", 1).substr(4) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "twice.ply"); }).find("twice.ply: header line 1: must be 'ply'"),
            std::string::npos);
  write_text(dir / "mesh.xyz1", triangle_header("ascii", 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(read_mesh(dir / "mesh.xyz1").triangles.size(), 1u) << "a PLY file by its content";
  write_text(dir / "notes.xyz1", "not a mesh, though ply appears in it\n");
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "notes.xyz1"); }).find("'.xyz1' is not a mesh format Assimp reads"),
            std::string::npos);
}

TEST(MeshFile, WhatIsNotARegularFileIsNamedForWhatItIs) {
  TempDir dir;
  std::filesystem::create_directory(dir / "folder.ply");
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "folder.ply"); }).find("folder.ply: cannot read the mesh: it is a directory"),
            std::string::npos);
  ASSERT_EQ(::mkfifo((dir / "fifo.ply").c_str(), 0600), 0);
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "fifo.ply"); }).find("fifo.ply: cannot read the mesh: it is not a regular file"),
            std::string::npos);
  std::filesystem::create_symlink(dir / "loop.ply", dir / "loop.ply");
  const std::string loop = input_error_of([&] { read_mesh(dir / "loop.ply"); });
  EXPECT_NE(loop.find("loop.ply: cannot read the mesh: Too many levels of symbolic links"), std::string::npos) << loop;
  EXPECT_NE(input_error_of([&] { read_mesh(dir / "absent.ply"); }).find("absent.ply: cannot read the mesh: no such file"),
            std::string::npos);
}

TEST(MeshFile, SceneMeshObjectsResolveRelativeToTheSceneAndCheckTheirKeys) {
  const Scene scene = parse_scene(R"({"materials": [{}], "objects": [{"type": "mesh", "file": "m/x.ply"}]})",
                                  "/data/shot/scene.json");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].kind, Object::Kind::mesh);
  EXPECT_EQ(scene.objects[0].file, std::filesystem::path("/data/shot/m/x.ply"));
  EXPECT_THROW(parse_scene(R"({"materials": [{}], "objects": [{"type": "mesh"}]})", "s.json"), InputError);
  EXPECT_THROW(parse_scene(R"({"materials": [{}], "objects": [{"type": "mesh", "file": ""}]})", "s.json"), InputError);
  EXPECT_THROW(parse_scene(R"({"materials": [{}], "objects": [{"type": "mesh", "file": "x", "radius": 1}]})", "s.json"),
               InputError);
}

TEST(SceneShapes, TransformsReachTrianglesMeshesSpheresAndPlanes) {
  TempDir dir;
  write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const glm::dmat4 outer = compose_transform({1, 2, 3}, {10, 20, 30}, {1, 2, 3});
  const glm::dmat4 inner = compose_transform({-1, 0, 0.5}, {0, 45, 0}, {2, 2, 2});
  Object mesh, sphere, plane, transform, nested;
  mesh.kind = Object::Kind::mesh;
  mesh.file = dir / "tri.obj";
  sphere.kind = Object::Kind::sphere;
  sphere.center = {0.5, 0, 0};
  sphere.radius = 0.25;
  plane.kind = Object::Kind::plane;
  plane.normal = {0, 2, 0};
  plane.offset = 1.5;
  nested.kind = Object::Kind::transform;
  nested.matrix = inner;
  nested.children = {mesh, sphere, plane};
  transform.kind = Object::Kind::transform;
  transform.matrix = outer;
  transform.children = {nested};
  const SceneShapes shapes = flatten_objects({transform});
  ASSERT_EQ(shapes.triangles.size(), 1u);
  ASSERT_EQ(shapes.spheres.size(), 1u);
  ASSERT_EQ(shapes.planes.size(), 1u);
  const glm::dmat4 world = outer * inner;
  const auto corners = shapes.corners(0);
  const glm::dvec3 expected[3] = {glm::dvec3(world * glm::dvec4(0, 0, 0, 1)), glm::dvec3(world * glm::dvec4(1, 0, 0, 1)),
                                  glm::dvec3(world * glm::dvec4(0, 1, 0, 1))};
  for (int k = 0; k < 3; ++k) EXPECT_LT(glm::length(corners[k] - expected[k]), 1e-12) << "corner " << k;

  // Points of the object-space plane y = 1.5 and sphere land on the world plane and inside the box.
  std::mt19937 rng(6502);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Box box = shapes.sphere_box(0);
  glm::dvec3 reached_lo(1e300), reached_hi(-1e300);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 on_plane = glm::dvec3(world * glm::dvec4(uniform(rng) * 5, 1.5, uniform(rng) * 5, 1));
    EXPECT_NEAR(glm::dot(shapes.planes[0].normal, on_plane), shapes.planes[0].offset, 1e-9);
    const glm::dvec3 direction = glm::normalize(glm::dvec3(uniform(rng), uniform(rng), uniform(rng)));
    const glm::dvec3 on_sphere = glm::dvec3(world * glm::dvec4(sphere.center + sphere.radius * direction, 1));
    EXPECT_TRUE(glm::all(glm::lessThanEqual(box.lo - 1e-12, on_sphere)) && glm::all(glm::lessThanEqual(on_sphere, box.hi + 1e-12)));
    reached_lo = glm::min(reached_lo, on_sphere);
    reached_hi = glm::max(reached_hi, on_sphere);
  }
  // ... and the box is tight: sampled points come within 1% of its size of every face.
  const glm::dvec3 size = box.hi - box.lo;
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LT(reached_lo[axis] - box.lo[axis], 0.01 * size[axis]) << "axis " << axis;
    EXPECT_LT(box.hi[axis] - reached_hi[axis], 0.01 * size[axis]) << "axis " << axis;
  }
}

TEST(SceneShapes, AMeshInstancedTwiceIsReadOnceAndPlacedTwice) {
  TempDir dir;
  write_ply(dir / "knot.ply", trefoil_knot(10, 4));
  Object mesh, moved;
  mesh.kind = Object::Kind::mesh;
  mesh.file = dir / "knot.ply";
  moved.kind = Object::Kind::transform;
  moved.matrix = compose_transform({10, 0, 0}, {0, 0, 0}, {1, 1, 1});
  moved.children = {mesh};
  const SceneShapes shapes = flatten_objects({mesh, moved});
  ASSERT_EQ(shapes.triangles.size(), 160u);
  for (std::size_t t = 0; t < 80; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(shapes.corners(t + 80)[k], shapes.corners(t)[k] + glm::dvec3(10, 0, 0));
}

// Every item in exactly one leaf, leaves of one group and within their boxes, children within
// their parents, depth within the limit.
void expect_valid(const Bvh& bvh, const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, int max_depth) {
  std::multiset<std::uint32_t> seen;
  std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
  int deepest = 0;
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    const Bvh::Node& node = bvh.nodes.at(index);
    if (node.leaf()) {
      ASSERT_LE(node.count, kBvhMaxLeafItems);
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const std::uint32_t item = bvh.order.at(i);
        seen.insert(item);
        EXPECT_EQ(groups[item], groups[bvh.order[node.first]]) << "a leaf mixes groups";
        EXPECT_TRUE(glm::all(glm::lessThanEqual(node.box.lo, boxes[item].lo)) &&
                    glm::all(glm::lessThanEqual(boxes[item].hi, node.box.hi)));
      }
      continue;
    }
    for (int c = 0; c < 2; ++c) {
      const Bvh::Node& child = bvh.nodes.at(node.first + c);
      EXPECT_TRUE(glm::all(glm::lessThanEqual(node.box.lo, child.box.lo)) &&
                  glm::all(glm::lessThanEqual(child.box.hi, node.box.hi)));
      stack.push_back({node.first + c, depth + 1});
    }
  }
  EXPECT_LE(deepest, max_depth);
  EXPECT_EQ(deepest, bvh.depth);
  std::size_t non_empty = 0;
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].empty()) continue;
    ++non_empty;
    EXPECT_EQ(seen.count(i), 1u) << "item " << i;
  }
  EXPECT_EQ(seen.size(), non_empty);
}

TEST(Bvh, RandomBoxesOfTwoGroups) {
  std::mt19937 rng(6502);
  std::uniform_real_distribution<double> position(-100.0, 100.0), size(0.0, 3.0);
  std::vector<Box> boxes;
  std::vector<std::uint8_t> groups;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 lo(position(rng), position(rng), position(rng));
    boxes.push_back({lo, lo + glm::dvec3(size(rng), size(rng), size(rng))});
    groups.push_back(static_cast<std::uint8_t>(i % 3 == 0));
  }
  boxes[17] = Box{};  // an empty box is left out
  const Bvh bvh = build_bvh(boxes, groups, 64);
  expect_valid(bvh, boxes, groups, 64);
  // The heuristic keeps a well-spread input shallow: far below the limit.
  EXPECT_LT(bvh.depth, 32);
}

// Big enough that subtrees are built on threads of their own and grafted (kParallelItems = 2^16).
TEST(Bvh, SubtreesBuiltInParallelGraftIntoOneValidTree) {
  std::mt19937 rng(1999);
  std::uniform_real_distribution<double> position(-1000.0, 1000.0), size(0.0, 2.0);
  std::vector<Box> boxes;
  for (int i = 0; i < 300000; ++i) {
    const glm::dvec3 lo(position(rng), position(rng), position(rng));
    boxes.push_back({lo, lo + glm::dvec3(size(rng), size(rng), size(rng))});
  }
  const std::vector<std::uint8_t> groups(boxes.size(), 0);
  const Bvh bvh = build_bvh(boxes, groups, 64);
  expect_valid(bvh, boxes, groups, 64);
  EXPECT_EQ(bvh.nodes.size() % 2, 1u);  // a root and pairs of children
}

TEST(Bvh, CoincidentAndDegenerateItemsStayWithinTheDepthLimit) {
  std::vector<Box> boxes(5000, Box{glm::dvec3(1.0), glm::dvec3(1.0)});  // every item one point
  std::vector<std::uint8_t> groups(5000, 0);
  for (int i = 0; i < 5000; i += 7) groups[i] = 1;
  const Bvh bvh = build_bvh(boxes, groups, 16);
  expect_valid(bvh, boxes, groups, 16);

  // Centres spread exponentially, the heuristic's worst case: every level splits off the few
  // items beyond 1/16 of the range, so unchecked it would nest about 4096 / 8 levels deep.
  std::vector<Box> spread;
  for (int i = 0; i < 4096; ++i) {
    const glm::dvec3 lo(std::ldexp(1.0, i / 8), 0.0, 0.0);
    spread.push_back({lo, lo + 1.0});
  }
  const std::vector<std::uint8_t> one_group(spread.size(), 0);
  const Bvh chain = build_bvh(spread, one_group, 14);
  expect_valid(chain, spread, one_group, 14);

  EXPECT_THROW(build_bvh(std::vector<Box>(9, boxes[0]), std::vector<std::uint8_t>(9, 0), 3), std::length_error);
  EXPECT_TRUE(build_bvh({}, {}, 64).nodes.empty());
}

// Every float primitive lies within the boxes on its path, wherever the eye is.
TEST(DeviceGeometry, RoundedBoxesHoldTheirFloatPrimitivesFarFromTheOrigin) {
  TempDir dir;
  write_ply(dir / "knot.ply", trefoil_knot(60, 6));
  Object mesh, ball, ellipsoid, plane;
  mesh.kind = Object::Kind::mesh;
  mesh.file = dir / "knot.ply";
  ball.kind = Object::Kind::sphere;
  ball.center = {1e6 + 0.3, 2, 0};
  ball.radius = 0.5;
  ellipsoid.kind = Object::Kind::transform;
  ellipsoid.matrix = compose_transform({1e6, 1, 1}, {20, 0, 70}, {1, 3, 0.5});
  ellipsoid.children = {ball};
  ellipsoid.children[0].center = {0, 0, 0};
  plane.kind = Object::Kind::plane;
  plane.normal = {0, 1, 0};
  Object moved;
  moved.kind = Object::Kind::transform;
  moved.matrix = compose_transform({1e6, 0, 0}, {0, 0, 0}, {1, 1, 1});
  moved.children = {mesh};
  const SceneBvh scene = build_scene_bvh(flatten_objects({moved, ball, ellipsoid, plane}), PHONGCL_BVH_MAX_DEPTH);
  const glm::dvec3 eye(1e6 + 3, 4, 9);
  const DeviceGeometry device = pack_device_geometry(scene, eye);
  ASSERT_EQ(device.primitives.size(), scene.bvh.order.size());
  ASSERT_EQ(device.planes.size(), 1u);
  EXPECT_FLOAT_EQ(device.planes[0].offset, -4.0f);  // y = 0 seen from y = 4

  // Walk the device tree; check each leaf's triangles against every box above them.
  struct Frame {
    unsigned node;
    std::vector<std::array<float, 6>> boxes;
  };
  std::size_t leaves_seen = 0;
  std::vector<Frame> stack{{0, {}}};
  while (!stack.empty()) {
    Frame frame = stack.back();
    stack.pop_back();
    const BvhNode& node = device.nodes.at(frame.node);
    for (int c = 0; c < 2; ++c) {
      const unsigned kind = node.kind_count[c] & PHONGCL_BVH_KIND_MASK;
      std::vector<std::array<float, 6>> boxes = frame.boxes;
      boxes.push_back({node.lo_x[c], node.lo_y[c], node.lo_z[c], node.hi_x[c], node.hi_y[c], node.hi_z[c]});
      if (kind == BVH_INNER) {
        stack.push_back({node.first[c], boxes});
        continue;
      }
      const unsigned count = node.kind_count[c] >> PHONGCL_BVH_KIND_BITS;
      for (unsigned k = node.first[c]; k < node.first[c] + count; ++k, ++leaves_seen) {
        if (kind != BVH_TRIANGLES) continue;
        for (const auto& corner : device.primitives[k].row)
          for (const auto& b : boxes)
            for (int axis = 0; axis < 3; ++axis) {
              EXPECT_LE(b[axis], corner[axis]);
              EXPECT_LE(corner[axis], b[axis + 3]);
            }
      }
    }
  }
  EXPECT_EQ(leaves_seen, device.primitives.size());

  // The ellipsoid's map sends its world surface to the unit sphere: |A (x - eye) + b| = 1.
  const std::size_t triangles = scene.shapes.triangles.size();
  for (std::size_t i = 0; i < device.primitives.size(); ++i) {
    if (scene.bvh.order[i] != triangles + 1) continue;
    const ShadowPrimitive& map = device.primitives[i];
    for (const glm::dvec3& d : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::normalize(glm::dvec3(1, -2, 3))}) {
      const glm::dvec3 x = glm::dvec3(ellipsoid.matrix * glm::dvec4(0.5 * d, 1.0)) - eye;
      glm::dvec3 u;
      for (int row = 0; row < 3; ++row)
        u[row] = map.row[row][0] * x.x + map.row[row][1] * x.y + map.row[row][2] * x.z + map.row[row][3];
      EXPECT_NEAR(glm::length(u), 1.0, 1e-5);
    }
  }
}

}  // namespace
}  // namespace phongcl
