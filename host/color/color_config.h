#pragma once
// An OpenColorIO config: where colour spaces, displays, views and looks come from. phongcl works in
// the config's scene_linear role (the working space): scene colours and G-buffer colour passes are
// converted into it (color/color_conversion.h), and display transforms start from it
// (color/display.h). Cheap to copy: copies share the loaded config and its compiled views.
//
// Installed with the public API: OpenColorIO stays behind the pointer.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../exr/pixel_window.h"  // Chromaticities

namespace phongcl {

class ColorConfig {
 public:
  // `which`: "" means the OCIO environment variable's config when it is set, else the built-in one;
  // "builtin" the built-in one (color/builtin_config.h); "blender" an installed Blender's (its
  // datafiles' colormanagement/config.ocio): the Blender executable `blender` names, else the one
  // blender_config_file() finds; anything else a config file. InputError naming the file (or the
  // variable) and OpenColorIO's complaint when it cannot be loaded.
  static ColorConfig load(const std::string& which = "", const std::string& blender = "");
  static ColorConfig builtin();
  // The config.ocio of the Blender executable `blender`, or when empty of an installed Blender
  // (BLENDER_SYSTEM_DATAFILES, $BLENDER, /usr/bin/blender, blender on PATH); InputError saying where it looked.
  static std::filesystem::path blender_config_file(const std::string& blender = "");

  std::string description() const;  // "built-in" or the file, and the config's name
  // For a config written for a newer OpenColorIO (Blender 5's): what was left out because this
  // OpenColorIO cannot run it, one line per view and per kind of entry, each saying why. Empty otherwise.
  const std::vector<std::string>& omitted() const;
  // The line of omitted() for that view of that display, when it was left out.
  std::optional<std::string> omitted_view(const std::string& display, const std::string& view) const;
  std::string working_space() const;
  std::vector<std::string> displays() const;
  std::string default_display() const;
  std::vector<std::string> views(const std::string& display) const;  // InputError for an unknown display
  std::string default_view(const std::string& display) const;
  std::vector<std::string> looks() const;
  std::vector<std::string> color_spaces() const;
  // The space a colour picker's values are in: the config's color_picking role, else the colour
  // space of the display's default view.
  std::string picker_space(const std::string& display) const;
  // The working space's primaries and white, when the config states them: the aces_interchange
  // role relates it to ACES2065-1, whose primaries are known (and the relation must be linear).
  std::optional<Chromaticities> working_chromaticities() const;
  // InputError naming the config and listing what it has, when `name` is not one of its colour
  // spaces (roles count); `option` says where the name came from ("--gbuffer-space").
  void check_color_space(const std::string& name, const std::string& option) const;

  struct Impl;  // color/config_impl.h
  const Impl& impl() const { return *impl_; }

 private:
  explicit ColorConfig(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<Impl> impl_;
};

}  // namespace phongcl
