#pragma once
// phongcl: deferred Phong shading of G-buffers with OpenCL, as a library.
//
//   phongcl::Scene scene = phongcl::load_scene("s.json");
//   phongcl::GBuffer gbuffer = phongcl::read_gbuffer("g.exr");  // layouts auto-detected
//   phongcl::Relighter relighter(scene, gbuffer);               // default device
//   phongcl::Image image = relighter.shade();                   // RGBA float
//   scene.lights[0].color = {2, 2, 2};
//   relighter.set_lights(scene.lights);
//   image = relighter.shade();
//   phongcl::write_exr("out.exr", image);
//   phongcl::ColorConfig blender = phongcl::ColorConfig::load("blender");   // OpenColorIO
//   phongcl::write_png(image, "out.png", phongcl::DisplayTransform(blender, {.view = "Filmic"}));
//   phongcl::RenderCompositor over("render.exr");               // relight over the render itself
//   phongcl::Image composite = over.relight(relighter, relighter.scene()).image;
//
// Errors are exceptions whose what() is the one-line message the command line prints: InputError
// (common/error.h) for bad files and values, std::invalid_argument and std::runtime_error otherwise.
// Link phongcl::phongcl (find_package(phongcl)).
#include "color/color_config.h"
#include "color/color_conversion.h"
#include "color/display.h"
#include "common/error.h"
#include "composite/relight_over.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "gbuffer_view.hpp"
#include "relighter.hpp"
#include "scene/scene.h"
#include "shading/precision.h"
