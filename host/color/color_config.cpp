#include "color/color_config.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

#include "color/builtin_config.h"
#include "color/chromaticities.h"
#include "color/config_downlevel.h"
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

// Where an installed Blender executable keeps its datafiles: official builds beside the binary in
// <version>/datafiles, distributions (and scripts/blender/make_root.sh's wrappers) in ../share/blender,
// Debian's without a version, others' with one.
std::vector<fs::path> datafiles_beside(const fs::path& binary) {
  std::error_code error;
  const fs::path real = fs::canonical(binary, error);
  if (error) return {};
  std::vector<fs::path> datafiles;
  for (const fs::path& root : {real.parent_path(), real.parent_path().parent_path() / "share" / "blender"}) {
    datafiles.push_back(root / "datafiles");
    for (const auto& entry : fs::directory_iterator(root, error))
      if (entry.is_directory(error)) datafiles.push_back(entry.path() / "datafiles");
  }
  return datafiles;
}

// Where Blender's datafiles are, for `blender`: the executable named, else BLENDER_SYSTEM_DATAFILES,
// the Blender that the BLENDER environment variable names (as the project's Blender scripts take it),
// distributions' shared directories and beside a `blender` on PATH.
std::vector<fs::path> blender_datafiles(const std::string& blender) {
  if (!blender.empty()) return datafiles_beside(blender);
  std::vector<fs::path> datafiles;
  if (const char* system = std::getenv("BLENDER_SYSTEM_DATAFILES")) datafiles.emplace_back(system);
  std::vector<fs::path> binaries;
  if (const char* named = std::getenv("BLENDER"); named != nullptr && *named != '\0') binaries.emplace_back(named);
  binaries.emplace_back("/usr/bin/blender");
  binaries.emplace_back("/usr/local/bin/blender");
  if (const char* path = std::getenv("PATH")) {
    std::string_view rest(path);
    while (!rest.empty()) {
      const std::size_t colon = rest.find(':');
      if (const fs::path binary = fs::path(rest.substr(0, colon)) / "blender"; ::access(binary.c_str(), X_OK) == 0)
        binaries.push_back(binary);
      if (colon == std::string_view::npos) break;
      rest.remove_prefix(colon + 1);
    }
  }
  for (const fs::path& binary : binaries)
    for (fs::path& found : datafiles_beside(binary)) datafiles.push_back(std::move(found));
  return datafiles;
}

// A config for a newer OpenColorIO (color/config_downlevel.h), read from its YAML with what this
// library cannot run left out, its files found beside it. The keys this library does not know
// (Blender 5's interop_id and interchange) are collected for one line rather than a warning each.
OCIO::ConstConfigRcPtr downlevelled(const fs::path& file, const DownlevelledConfig& config, ColorConfig::Impl& impl) {
  static std::mutex logging;
  const std::lock_guard lock(logging);
  static const std::regex unknown_key("unknown key '([^']*)'");
  std::set<std::string> unknown_keys;
  OCIO::SetLoggingFunction([&](const char* message) {
    if (std::cmatch match; std::regex_search(message, match, unknown_key))
      unknown_keys.insert(match[1]);
    else
      std::cerr << message;
  });
  std::istringstream yaml(config.yaml);
  OCIO::ConfigRcPtr ocio;
  try {
    ocio = OCIO::Config::CreateFromStream(yaml)->createEditableCopy();
  } catch (...) {
    OCIO::ResetToDefaultLoggingFunction();
    throw;
  }
  OCIO::ResetToDefaultLoggingFunction();
  ocio->setWorkingDir(fs::absolute(file).parent_path().c_str());
  impl.omitted_views = config.views;
  for (const OmittedView& view : config.views) impl.notes.push_back(view.line());
  impl.notes.insert(impl.notes.end(), config.others.begin(), config.others.end());
  if (!unknown_keys.empty())
    impl.notes.push_back("keys ignored, unknown to OpenColorIO " + std::string(OCIO::GetVersion()) + ": " +
                    joined({unknown_keys.begin(), unknown_keys.end()}));
  return ocio;
}

std::shared_ptr<ColorConfig::Impl> from_file(const fs::path& file) {
  require_regular_file(file, "OCIO config");
  auto impl = std::make_shared<ColorConfig::Impl>();
  try {
    try {
      impl->ocio = OCIO::Config::CreateFromFile(file.c_str());
    } catch (const OCIO::Exception&) {
      std::ifstream stream(file);
      const std::string text{std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
      std::optional<DownlevelledConfig> older;
      try {
        older = downlevel_config(text);
      } catch (const std::runtime_error&) {
      }
      if (!older) throw;  // OpenColorIO's own complaint says more than the YAML parser's
      impl->ocio = downlevelled(file, *older, *impl);
    }
    impl->ocio->validate();
  } catch (const OCIO::Exception& error) {
    throw InputError(file, "not a usable OCIO config: " + one_line(error.what()));
  }
  const std::string name = impl->ocio->getName();
  impl->description = file.string() + (name.empty() ? "" : " (" + name + ")");
  if (!impl->notes.empty())
    impl->description += ", read by OpenColorIO " + std::string(OCIO::GetVersion()) + " without what it cannot run";
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

fs::path ColorConfig::blender_config_file(const std::string& blender) {
  for (const fs::path& datafiles : blender_datafiles(blender))
    if (const fs::path candidate = datafiles / "colormanagement" / "config.ocio"; fs::is_regular_file(candidate))
      return candidate;
  if (!blender.empty())
    throw InputError(blender, "no Blender OCIO config beside it (looked for datafiles/colormanagement/config.ocio beside "
                              "the executable, in <version>/ there and in ../share/blender)");
  throw InputError("--ocio blender: no Blender OCIO config found (looked for datafiles/colormanagement/config.ocio in "
                   "BLENDER_SYSTEM_DATAFILES, beside $BLENDER, /usr/bin/blender, /usr/local/bin/blender and blender on "
                   "PATH); name the Blender with --blender PATH, or give the path of its config.ocio");
}

ColorConfig ColorConfig::builtin() {
  auto impl = std::make_shared<Impl>();
  impl->ocio = make_builtin_config();
  impl->description = "built-in (sRGB display: reinhard, aces, clamp)";
  return ColorConfig(std::move(impl));
}

ColorConfig ColorConfig::load(const std::string& which, const std::string& blender) {
  if (!blender.empty() && which != "blender")
    throw InputError("--blender " + blender + " names the Blender whose config --ocio blender loads; --ocio is '" + which + "'");
  if (which == "builtin") return builtin();
  if (which == "blender") return ColorConfig(from_file(blender_config_file(blender)));
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

const std::vector<std::string>& ColorConfig::omitted() const { return impl_->notes; }

std::optional<std::string> ColorConfig::omitted_view(const std::string& display, const std::string& view) const {
  for (const OmittedView& omitted : impl_->omitted_views)
    if (omitted.display == display && omitted.view == view) return omitted.line();
  return std::nullopt;
}

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
