#pragma once
// A config written for a newer OpenColorIO than the one phongcl is linked with, made readable by it.
// Blender 5's config says `ocio_profile_version: 2.5` and uses ACES 2.0's built-in transforms, and
// OpenColorIO 2.1 refuses the whole file for either. Here the config is read as YAML, everything that
// needs a built-in transform this library lacks is left out, then everything that refers to what was
// left out (views, looks, roles, rules), and the profile version is lowered to the library's. What
// remains runs exactly as the newer library would run it: the transforms themselves are untouched.
#include <optional>
#include <string>
#include <vector>

namespace phongcl {

struct OmittedView {
  std::string display, view;
  std::string why;  // "it uses 'ACES 2.0 Rec.1886', which OpenColorIO 2.1.2 cannot run (it needs ...)"

  std::string line() const { return "view '" + view + "' of display '" + display + "' left out: " + why; }
};

struct DownlevelledConfig {
  std::string yaml;                // the config as this OpenColorIO reads it
  std::vector<OmittedView> views;  // every view left out
  std::vector<std::string> others;  // one line per kind of anything else left out, with why
};

// nullopt when this OpenColorIO reads the config's profile version itself. std::runtime_error with
// the YAML parser's message when the text is not YAML (the caller names the file).
std::optional<DownlevelledConfig> downlevel_config(const std::string& yaml);

}  // namespace phongcl
