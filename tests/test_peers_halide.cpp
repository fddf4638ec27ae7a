// The Halide peer of the throughput benchmark (lab/peers/halide_peer, its own process) against the
// double reference, and the packed-input file it reads. The peer's tests skip where Halide is not
// installed (the peer is not built then).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "opencl_required.h"
#include "peers/halide_peer.h"
#include "peers/packed_file.h"
#include "cli_runner.h"
#include "shading_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

std::optional<std::filesystem::path> halide_peer() {
#ifdef PHONGCL_HALIDE_PEER_EXE
  return std::filesystem::path(PHONGCL_HALIDE_PEER_EXE);
#else
  return std::nullopt;
#endif
}

TEST(PackedFile, RoundTripsFrameAndScene) {
  const auto [scene, gbuffer] = random_scene(RandomSceneSpec{}, 11);
  const PackedFrame frame = pack_frame(gbuffer, scene);
  const PackedScene packed = pack_scene(scene);
  const testing::TempDir dir("packed_file");
  write_packed_inputs(dir / "in.packed", frame, packed);
  const PackedInputs read = read_packed_inputs(dir / "in.packed");
  EXPECT_EQ(read.frame.pixels, frame.pixels);
  EXPECT_EQ(read.frame.px, frame.px);
  EXPECT_EQ(read.frame.nz, frame.nz);
  EXPECT_EQ(read.frame.material, frame.material);
  EXPECT_EQ(read.scene.shininess, packed.shininess);
  EXPECT_EQ(read.scene.point_b, packed.point_b);
  EXPECT_EQ(read.scene.dir_x, packed.dir_x);
}

TEST(PackedFile, RefusesTruncatedAndForeignFilesNamingThem) {
  const auto [scene, gbuffer] = random_scene(RandomSceneSpec{}, 12);
  const testing::TempDir dir("packed_file");
  const auto file = dir / "in.packed";
  write_packed_inputs(file, pack_frame(gbuffer, scene), pack_scene(scene));
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 5);
  try {
    read_packed_inputs(file);
    FAIL() << "a truncated file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  std::ofstream(file, std::ios::binary) << "not a packed file at all";
  EXPECT_THROW(read_packed_inputs(file), InputError);
}

TEST(HalidePeer, MatchesReferenceOnSmallRandomFrames) {
  const auto peer = halide_peer();
  if (!peer) GTEST_SKIP() << "Halide not installed: no phongcl-halide-peer";
  unsigned seed = 4004;
  for (int lights : {0, 16}) {  // one JIT compile each, a few seconds
    RandomSceneSpec spec;
    spec.width = lights == 16 ? 64 : 37;
    spec.height = lights == 16 ? 48 : 23;
    spec.point_lights = (lights + 1) / 2;
    spec.directional_lights = lights / 2;
    const auto [scene, gbuffer] = random_scene(spec, ++seed);
    Image image = image_like(gbuffer);
    const HalidePeerRun run = run_halide_peer(*peer, pack_frame(gbuffer, scene), pack_scene(scene), 2, 1e4, image.rgba.data());
    EXPECT_EQ(run.times_ms.size(), 2u);
    EXPECT_GT(run.compile_ms, 0.0);
    const ErrorStats stats = shading_error(image, reference_image(scene, gbuffer), testing::shaded_mask(gbuffer));
    EXPECT_LE(stats.max_rel, kRelativeBound) << lights << " lights, schedule " << run.schedule << ": " << testing::describe_worst(stats);
    EXPECT_EQ(stats.nonfinite_mismatches, 0u);
    testing::expect_background_exact(image, scene, gbuffer);
  }
}

TEST(HalidePeer, FailsWithItsOwnMessageOnBadInput) {
  const auto peer = halide_peer();
  if (!peer) GTEST_SKIP() << "Halide not installed: no phongcl-halide-peer";
  const testing::TempDir dir("halide_peer");
  std::ostringstream command;
  command << peer->string() << " --input " << (dir / "missing.packed").string() << " --output " << (dir / "out").string()
          << " 2>" << (dir / "err").string();
  EXPECT_NE(std::system(command.str().c_str()), 0);
  std::ifstream err(dir / "err");
  const std::string message((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("missing.packed: cannot open"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// `bench --throughput` on a tiny frame, run by `phongcl` (or a copy of phongcl-lab); its JSON rows.
nlohmann::json throughput_rows(const std::filesystem::path& phongcl, const testing::TempDir& dir) {
  std::ostringstream command;
  command << "cd '" PHONGCL_SOURCE_DIR "' && '" << phongcl.string()
          << "' bench --throughput --scene scenes/default/scene.json --sizes 48x32 --lights 1 --runs 1 --json '"
          << (dir / "t.json").string() << "' </dev/null >'" << (dir / "out").string() << "' 2>&1";
  EXPECT_EQ(std::system(command.str().c_str()), 0) << testing::read_text(dir / "out");
  return nlohmann::json::parse(testing::read_text(dir / "t.json")).at("results");
}

const nlohmann::json* halide_row(const nlohmann::json& rows) {
  for (const auto& row : rows) {
    if (row.at("impl") == "halide") return &row;
  }
  return nullptr;
}

TEST(ThroughputBench, HalideRowHasMeasuredFiguresBesidePhongcl) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  if (!halide_peer()) GTEST_SKIP() << "Halide not installed: no phongcl-halide-peer";
  const testing::TempDir dir("bench_halide");
  const nlohmann::json rows = throughput_rows(PHONGCL_EXE, dir);
  const nlohmann::json* row = halide_row(rows);
  ASSERT_NE(row, nullptr) << rows.dump(1);
  EXPECT_FALSE(row->contains("not_run")) << row->dump();
  EXPECT_GT(row->at("median_ms").get<double>(), 0.0);
  EXPECT_LE(row->at("max_rel_err").get<double>(), kRelativeBound);
  EXPECT_GT(row->at("compile_ms").get<double>(), 0.0);
  EXPECT_FALSE(row->at("schedule").get<std::string>().empty());
}

TEST(ThroughputBench, HalideRowSaysSkipWithoutThePeerAndHasNoFigures) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const testing::TempDir dir("bench_no_halide");
  // The benchmark runs in phongcl-lab (phongcl hands it over); a copy of that with no peer beside it.
  const auto lone_lab = dir / "phongcl-lab";
  std::filesystem::copy_file(std::filesystem::path(PHONGCL_EXE).parent_path() / "phongcl-lab", lone_lab);
  const nlohmann::json rows = throughput_rows(lone_lab, dir);
  const nlohmann::json* row = halide_row(rows);
  ASSERT_NE(row, nullptr) << rows.dump(1);
  EXPECT_EQ(row->at("not_run").get<std::string>().rfind("SKIP: Halide not installed", 0), 0u) << row->dump();
  EXPECT_TRUE(row->at("median_ms").is_null());
  EXPECT_TRUE(row->at("max_rel_err").is_null());
}

}  // namespace
}  // namespace phongcl
