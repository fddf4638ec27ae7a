#include "peers/packed_file.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <vector>

#include "common/error.h"

namespace phongcl {

namespace {

constexpr std::array<char, 8> kMagic{'P', 'H', 'P', 'K', 'D', '0', '0', '1'};

// Every plane in file order: the frame's float planes, then the scene's tables in three groups of
// equal lengths (materials, point lights, directional lights).
template <typename Frame>
auto frame_planes(Frame& f) {
  return std::array{&f.px, &f.py, &f.pz, &f.nx, &f.ny, &f.nz};
}
template <typename Scene>
auto scene_groups(Scene& s) {
  return std::array<std::vector<decltype(&s.alpha)>, 3>{
      {{&s.ambient_r, &s.ambient_g, &s.ambient_b, &s.kd_r, &s.kd_g, &s.kd_b, &s.ks_r, &s.ks_g, &s.ks_b, &s.shininess, &s.alpha},
       {&s.point_x, &s.point_y, &s.point_z, &s.point_r, &s.point_g, &s.point_b},
       {&s.dir_x, &s.dir_y, &s.dir_z, &s.dir_r, &s.dir_g, &s.dir_b}}};
}

class Writer {
 public:
  explicit Writer(const std::filesystem::path& file) : file_(file), out_(file, std::ios::binary) {
    if (!out_) throw InputError(file, "cannot create");
  }
  void bytes(const void* data, std::size_t size) { out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(size)); }
  template <typename Vector>
  void plane(const Vector& v) {
    const std::uint64_t count = v.size();
    bytes(&count, sizeof count);
    bytes(v.data(), count * sizeof(v[0]));
  }
  void finish() {
    if (!out_.flush()) throw InputError(file_, "cannot write");
  }

 private:
  std::filesystem::path file_;
  std::ofstream out_;
};

class Reader {
 public:
  explicit Reader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InputError(file, "cannot open");
  }
  void bytes(void* data, std::size_t size) {
    if (!in_.read(static_cast<char*>(data), static_cast<std::streamsize>(size))) throw InputError(file_, "truncated packed input");
  }
  template <typename Vector>
  void plane(Vector& v, std::optional<std::uint64_t> expected) {
    std::uint64_t count = 0;
    bytes(&count, sizeof count);
    if ((expected && count != *expected) || count > (std::uint64_t{1} << 34)) {
      throw InputError(file_, "plane of " + std::to_string(count) + " entries, inconsistent with the others");
    }
    v.resize(count);
    bytes(v.data(), count * sizeof(v[0]));
  }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
};

}  // namespace

void write_packed_inputs(const std::filesystem::path& file, const PackedFrame& frame, const PackedScene& scene) {
  Writer out(file);
  out.bytes(kMagic.data(), kMagic.size());
  const std::uint64_t pixels = frame.pixels;
  out.bytes(&pixels, sizeof pixels);
  for (const auto* plane : frame_planes(frame)) out.plane(*plane);
  out.plane(frame.material);
  for (const auto& group : scene_groups(scene)) {
    for (const auto* table : group) out.plane(*table);
  }
  out.finish();
}

PackedInputs read_packed_inputs(const std::filesystem::path& file) {
  Reader in(file);
  std::array<char, kMagic.size()> magic{};
  in.bytes(magic.data(), magic.size());
  if (magic != kMagic) throw InputError(file, "not a packed peer input (wrong magic)");
  PackedInputs inputs;
  std::uint64_t pixels = 0;
  in.bytes(&pixels, sizeof pixels);
  const std::uint64_t padded = (pixels + kPeerPadding - 1) / kPeerPadding * kPeerPadding;
  if (padded == 0) throw InputError(file, "packed input has no pixels");
  inputs.frame.pixels = pixels;
  for (auto* plane : frame_planes(inputs.frame)) in.plane(*plane, padded);
  in.plane(inputs.frame.material, padded);
  for (const auto& group : scene_groups(inputs.scene)) {
    in.plane(*group.front(), std::nullopt);  // the group's length: any
    for (std::size_t t = 1; t < group.size(); ++t) in.plane(*group[t], group.front()->size());
  }
  const auto materials = static_cast<std::int64_t>(inputs.scene.alpha.size());
  for (std::int32_t m : inputs.frame.material) {
    if (m < kPeerBackground || m + 1 >= materials) throw InputError(file, "material index " + std::to_string(m) + " out of range");
  }
  return inputs;
}

}  // namespace phongcl
