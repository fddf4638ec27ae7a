#pragma once
// The camera a G-buffer's header states, from OpenEXR's standard attributes (docs/formats.md
// "Cameras from the file"):
//   worldToCamera (M44f): world to the renderer's camera space, which is left-handed: +x right,
//     +y up in the image, +z the viewing direction, the origin at the eye (RenderMan's camera space).
//   worldToNDC (M44f): world to NDC, where (0, 0) and (1, 1) are the display window's upper left
//     and lower right corners, x right and y down (RenderMan's NDC).
// Both are Imath matrices, which multiply row vectors from the left (p' = p * M, translation in
// the last row). Arnold, RenderMan, 3Delight and Mantra write them. Blender writes neither
// (scripts/blender/export_scene.py exports its camera).
#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace phongcl {

struct FileCamera {
  std::array<double, 3> eye{}, forward{}, up{};  // world space; forward and up unit length
  double fov_y_deg = 0.0;                        // vertical, over the display window's height
  int width = 0, height = 0;                     // the display window
};

// The file's camera, or none when the header lacks worldToCamera or worldToNDC. Throws InputError
// naming the file when they state no camera phongcl can use: a singular matrix, a projection
// whose axis does not meet the image centre (a lens shift), non-square pixels, or a camera that
// looks backwards.
std::optional<FileCamera> read_file_camera(const std::filesystem::path& file);

}  // namespace phongcl
