#include "color/color_config.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <string_view>

#include "color/builtin_config.h"
#include "color/chromaticities.h"
#include "color/config_impl.h"
#include "common/error.h"
#include "common/regular_file.h"
#include "common/joined.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;
namespace fs = std::filesystem;

namespace {

// OpenColorIO's messages can span lines; ours are one.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// Where Blender keeps its datafiles: BLENDER_SYSTEM_DATAFILES, distributions' shared directory
// (Debian's without a version, others' with one), and beside a `blender` on PATH (official builds
// keep <version>/datafiles next to the binary).
std::vector<fs::path> blender_config_candidates() {
  std::vector<fs::path> candidates;
  const auto add_datafiles = [&](const fs::path& datafiles) { candidates.push_back(datafiles / "colormanagement" / "config.ocio"); };
  if (const char* datafiles = std::getenv("BLENDER_SYSTEM_DATAFILES")) add_datafiles(datafiles);
  std::vector<fs::path> roots{"/usr/share/blender", "/usr/local/share/blender"};
  if (const char* path = std::getenv("PATH")) {
    std::string_view rest(path);
    while (!rest.empty()) {
      const std::size_t colon = rest.find(':');
      const fs::path binary = fs::path(rest.substr(0, colon)) / "blender";
      std::error_code error;
      if (::access(binary.c_str(), X_OK) == 0) {
        const fs::path real = fs::canonical(binary, error);
        if (!error) {
          roots.push_back(real.parent_path());
          roots.push_back(real.parent_path().parent_path() / "share" / "blender");
        }
      }
      if (colon == std::string_view::npos) break;
      rest.remove_prefix(colon + 1);
    }
  }
  for (const fs::path& root : roots) {
    add_datafiles(root / "datafiles");
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(root, error))
      if (entry.is_directory(error)) add_datafiles(entry.path() / "datafiles");  // <version>/datafiles
  }
  return candidates;
}

std::shared_ptr<ColorConfig::Impl> from_file(const fs::path& file) {
  require_regular_file(file, "OCIO config");
  auto impl = std::make_shared<ColorConfig::Impl>();
  try {
    impl->ocio = OCIO::Config::CreateFromFile(file.c_str());
    impl->ocio->validate();
  } catch (const OCIO::Exception& error) {
    throw InputError(file, "not a usable OCIO config: " + one_line(error.what()));
  }
  const std::string name = impl->ocio->getName();
  impl->description = file.string() + (name.empty() ? "" : " (" + name + ")");
  return impl;
}

std::vector<std::string> names(int count, const std::function<const char*(int)>& name_of) {
  std::vector<std::string> result;
  for (int i = 0; i < count; ++i) result.emplace_back(name_of(i));
  return result;
}

// A transform applied to a handful of colours, as a 3x3 matrix when it is one: the response to the
// unit vectors must predict the response to other colours (no offset, no curve).
std::optional<Matrix3> as_linear_matrix(const OCIO::ConstCPUProcessorRcPtr& cpu) {
  float probe[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}, {0.25f, 2.0f, 0.5f}, {4.0f, 0.125f, 1.0f}};
  OCIO::PackedImageDesc image(&probe[0][0], 6, 1, 3);
  cpu->apply(image);
  Matrix3 m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = probe[j][i];
  const float inputs[2][3] = {{0.25f, 2.0f, 0.5f}, {4.0f, 0.125f, 1.0f}};
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i) {
      const double predicted = m[i][0] * inputs[k][0] + m[i][1] * inputs[k][1] + m[i][2] * inputs[k][2];
      const double scale = std::max({1.0, std::abs(predicted)});
      if (std::abs(probe[3][i]) > 1e-6 || std::abs(probe[4 + k][i] - predicted) > 1e-4 * scale) return std::nullopt;
    }
  return m;
}

}  // namespace

fs::path ColorConfig::blender_config_file() {
  const std::vector<fs::path> candidates = blender_config_candidates();
  for (const fs::path& candidate : candidates)
    if (fs::is_regular_file(candidate)) return candidate;
  throw InputError("--ocio blender: no Blender OCIO config found (looked for datafiles/colormanagement/config.ocio in "
                   "BLENDER_SYSTEM_DATAFILES, /usr/share/blender, /usr/local/share/blender and beside blender on PATH); "
                   "give the path of Blender's config.ocio");
}

ColorConfig ColorConfig::builtin() {
  auto impl = std::make_shared<Impl>();
  impl->ocio = make_builtin_config();
  impl->description = "built-in (sRGB display: reinhard, aces, clamp)";
  return ColorConfig(std::move(impl));
}

ColorConfig ColorConfig::load(const std::string& which) {
  if (which == "builtin") return builtin();
  if (which == "blender") return ColorConfig(from_file(blender_config_file()));
  if (!which.empty()) return ColorConfig(from_file(which));
  const char* environment = std::getenv("OCIO");
  if (environment == nullptr || *environment == '\0') return builtin();
  try {
    return ColorConfig(from_file(environment));
  } catch (const InputError& error) {
    throw InputError(std::string("the OCIO environment variable names ") + error.what());
  }
}

std::string ColorConfig::description() const { return impl_->description; }

std::string ColorConfig::working_space() const {
  const OCIO::ConstColorSpaceRcPtr space = impl_->ocio->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
  if (!space) throw InputError(impl_->description + ": the config has no scene_linear role (phongcl's working space)");
  return space->getName();
}

std::vector<std::string> ColorConfig::displays() const {
  return names(impl_->ocio->getNumDisplays(), [&](int i) { return impl_->ocio->getDisplay(i); });
}

std::string ColorConfig::default_display() const { return impl_->ocio->getDefaultDisplay(); }

std::vector<std::string> ColorConfig::views(const std::string& display) const {
  const std::vector<std::string> all = displays();
  if (std::find(all.begin(), all.end(), display) == all.end())
    throw InputError(impl_->description + ": no display '" + display + "' (displays: " + joined(all) + ")");
  return names(impl_->ocio->getNumViews(display.c_str()), [&](int i) { return impl_->ocio->getView(display.c_str(), i); });
}

std::string ColorConfig::default_view(const std::string& display) const {
  views(display);  // checks the name
  return impl_->ocio->getDefaultView(display.c_str());
}

std::vector<std::string> ColorConfig::looks() const {
  return names(impl_->ocio->getNumLooks(), [&](int i) { return impl_->ocio->getLookNameByIndex(i); });
}

std::vector<std::string> ColorConfig::color_spaces() const {
  return names(impl_->ocio->getNumColorSpaces(), [&](int i) { return impl_->ocio->getColorSpaceNameByIndex(i); });
}

std::string ColorConfig::picker_space(const std::string& display) const {
  if (const auto space = impl_->ocio->getColorSpace(OCIO::ROLE_COLOR_PICKING)) return space->getName();
  const std::string view = default_view(display);
  return impl_->ocio->getDisplayViewColorSpaceName(display.c_str(), view.c_str());
}

std::optional<Chromaticities> ColorConfig::working_chromaticities() const {
  if (!impl_->ocio->hasRole(OCIO::ROLE_INTERCHANGE_SCENE)) return std::nullopt;
  try {
    auto group = OCIO::GroupTransform::Create();
    auto to_aces = OCIO::ColorSpaceTransform::Create();
    to_aces->setSrc(OCIO::ROLE_SCENE_LINEAR);
    to_aces->setDst(OCIO::ROLE_INTERCHANGE_SCENE);
    group->appendTransform(to_aces);
    auto to_xyz = OCIO::BuiltinTransform::Create();
    to_xyz->setStyle("UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD");
    group->appendTransform(to_xyz);
    const auto matrix = as_linear_matrix(impl_->ocio->getProcessor(group)->getDefaultCPUProcessor());
    if (!matrix) return std::nullopt;
    return chromaticities_of(*matrix);
  } catch (const OCIO::Exception&) {
    return std::nullopt;  // a role naming a space the config cannot reach: nothing stated
  }
}

void ColorConfig::check_color_space(const std::string& name, const std::string& option) const {
  if (impl_->ocio->getColorSpace(name.c_str())) return;
  throw InputError(option + " '" + name + "': no such colour space in " + impl_->description + " (colour spaces: " +
                   joined(color_spaces()) + ")");
}

}  // namespace phongcl
