#include "gbuffer/layout_presets.h"

#include <algorithm>
#include <limits>
#include <set>
#include <stdexcept>

#include "common/error.h"
#include "common/joined.h"
#include "gbuffer/gbuffer_layout.h"

namespace phongcl {

namespace {

constexpr float kNoNoHitDepth = std::numeric_limits<float>::infinity();

bool has(const std::vector<std::string>& channels, const std::string& name) {
  return std::find(channels.begin(), channels.end(), name) != channels.end();
}

std::vector<std::string> with_suffixes(const std::string& base, const char* a, const char* b, const char* c) {
  return {base + a, base + b, base + c};
}
std::vector<std::string> xyz(const std::string& base) { return with_suffixes(base, ".X", ".Y", ".Z"); }
std::vector<std::string> rgb(const std::string& base) { return with_suffixes(base, ".R", ".G", ".B"); }

// The native layout, from the table the writer uses too, so reading and writing cannot drift.
LayoutSpec phongcl_spec() {
  GBuffer g;
  const auto pass_of = [&](const Plane* plane) {
    const std::pair<Pass, const Plane*> planes[] = {
        {Pass::position, &g.position[0]}, {Pass::normal, &g.normal[0]}, {Pass::material, &g.material},
        {Pass::ka, &g.ka[0]},             {Pass::kd, &g.kd[0]},         {Pass::ks, &g.ks[0]},
        {Pass::shininess, &g.shininess}};
    for (const auto& [pass, candidate] : planes)
      if (candidate == plane) return pass;
    return Pass::material;  // unreachable: the table covers every plane of gbuffer_layout
  };
  LayoutSpec spec{Layout::phongcl, "", {}, false, false, DepthConvention::distance, "", kNoNoHitDepth};
  for (const auto& group : gbuffer_layout(g)) {
    PassSource source;
    for (const auto& channel : group.channels) source.channels.emplace_back(channel.name);
    source.label = source.channels.front().substr(0, source.channels.front().find('.'));
    spec.passes.push_back({pass_of(group.channels.front().plane), group.required, {source}});
  }
  return spec;
}

// Blender writes "<layer>.<pass>.<channel>" into multilayer EXRs; passes renamed in 2.8x-4.x, so
// both generations of names are accepted. A File Output node writes "<pass>.<channel>", one-channel
// passes as "<pass>.V". Cycles' and EEVEE's Depth is view-space z (measured on their renders:
// tests/test_renderers.cpp).
LayoutSpec blender_spec(const std::string& layer, bool file_output) {
  const std::string p = layer.empty() ? "" : layer + ".";
  const std::string scalar = file_output ? ".V" : ".X";
  std::vector<PassSource> alpha = {{"Combined.A", {p + "Combined.A"}}, {"A", {"A"}}};
  if (file_output) alpha = {{"Alpha", {"Alpha.V"}}, {"Image.A", {"Image.A"}}};
  std::vector<PassSource> beauty = {{"Combined", rgb(p + "Combined")}};
  if (file_output) beauty = {{"Image", rgb("Image")}};
  return {Layout::blender,
          layer,
          {{Pass::position, true, {{"Position", xyz(p + "Position")}}},
           {Pass::normal, true, {{"Normal", xyz(p + "Normal")}}},
           {Pass::depth, false, {{"Depth", {p + (file_output ? "Depth.V" : "Depth.Z")}}}},
           {Pass::kd, false, {{"DiffCol", rgb(p + "DiffCol")}, {"Diffuse Color", rgb(p + "Diffuse Color")}}},
           {Pass::ks, false, {{"GlossCol", rgb(p + "GlossCol")}, {"Glossy Color", rgb(p + "Glossy Color")}}, false},
           {Pass::material, false, {{"IndexMA", {p + "IndexMA" + scalar}}, {"Material Index", {p + "Material Index" + scalar}}}},
           {Pass::alpha, false, alpha}},
          true,
          file_output,
          DepthConvention::view_z,
          "Blender's Depth pass is view-space z",
          65504.0f,
          beauty};
}

// The File Output node's unprefixed pass names.
bool looks_like_file_output(const std::vector<std::string>& channels) {
  return has(channels, "Normal.X") || has(channels, "Position.X") || has(channels, "Depth.V");
}

LayoutSpec aov_spec() {
  const auto vector_sources = [](const std::string& local, const std::string& world) {
    return std::vector<PassSource>{{local, xyz(local)}, {local, rgb(local)}, {world, xyz(world)}, {world, rgb(world)}};
  };
  return {Layout::aov,
          "",
          {{Pass::position, true, vector_sources("P", "Pworld")},
           {Pass::normal, true, vector_sources("N", "Nworld")},
           {Pass::depth, false, {{"Z", {"Z"}}}},
           {Pass::kd, false, {{"diffuse_albedo", rgb("diffuse_albedo")}, {"albedo", rgb("albedo")}}},
           {Pass::ks, false, {{"specular_albedo", rgb("specular_albedo")}}},
           {Pass::material, false, {{"material", {"material"}}}},
           {Pass::alpha, false, {{"A", {"A"}}}}},
          true,
          false,
          DepthConvention::distance,
          "the aov layout's Z is taken as distance along the ray (Arnold's Z; RenderMan's z is viewz)",
          kNoNoHitDepth,
          {{"RGBA", rgb("RGBA")}, {"beauty", rgb("beauty")}, {"RGB", {"R", "G", "B"}}}};
}

// The passes phongcl requires, mapped by the user alone.
LayoutSpec custom_spec() {
  return {Layout::custom, "", {{Pass::position, true, {}}, {Pass::normal, true, {}}}, true, false,
          DepthConvention::distance, "the default for a custom mapping", kNoNoHitDepth};
}

// "<layer>" of every channel "<layer>.<pass>.<chan>" whose pass and channel are Blender's.
std::vector<std::string> blender_layers(const std::vector<std::string>& channels) {
  static const char* const kMarkers[] = {".Normal.X", ".Position.X", ".Depth.Z"};
  std::set<std::string> layers;
  for (const auto& channel : channels)
    for (const char* marker : kMarkers) {
      const std::string suffix = marker;
      if (channel.size() > suffix.size() && channel.ends_with(suffix))
        layers.insert(channel.substr(0, channel.size() - suffix.size()));
    }
  return {layers.begin(), layers.end()};
}

std::string pick_view_layer(const std::vector<std::string>& channels, const std::filesystem::path& file) {
  const auto layers = blender_layers(channels);
  if (layers.size() == 1) return layers.front();
  if (has(layers, "ViewLayer")) return "ViewLayer";
  if (layers.empty())
    throw InputError(file, "no Blender view layer (channels like ViewLayer.Normal.X) (found: " + joined(channels, ", ", "none") + ")");
  throw InputError(file, "several Blender view layers (" + joined(layers, ", ", "none") + "): choose one with --view-layer");
}

bool looks_like_aov(const std::vector<std::string>& channels) {
  const auto all_of = [&](const std::vector<std::string>& names) {
    return std::all_of(names.begin(), names.end(), [&](const std::string& name) { return has(channels, name); });
  };
  for (const char* name : {"Pworld", "Nworld"})
    if (has(channels, xyz(name)[0]) || has(channels, rgb(name)[0])) return true;
  if (has(channels, "P.R") || has(channels, "N.R")) return true;
  return all_of(xyz("P")) && all_of(xyz("N")) && !has(channels, "material");
}

constexpr std::pair<Layout, const char*> kLayoutNames[] = {{Layout::automatic, "auto"},
                                                         {Layout::phongcl, "phongcl"},
                                                         {Layout::blender, "blender"},
                                                         {Layout::aov, "aov"},
                                                         {Layout::custom, "custom"}};

}  // namespace

const char* layout_name(Layout layout) {
  for (const auto& [candidate, name] : kLayoutNames)
    if (candidate == layout) return name;
  return "?";
}

Layout parse_layout(std::string_view name) {
  // custom is what auto reports for a file only --channel describes, not a choice of its own.
  for (const auto& [layout, known] : kLayoutNames)
    if (name == known && layout != Layout::custom) return layout;
  throw InputError("unknown --layout '" + std::string(name) + "' (choose auto, phongcl, blender or aov)");
}

LayoutSpec layout_spec(Layout layout, const std::string& view_layer, const std::vector<std::string>& channels,
                       const std::filesystem::path& file) {
  switch (layout) {
    case Layout::phongcl: return phongcl_spec();
    case Layout::blender:
      if (view_layer.empty() && blender_layers(channels).empty() && looks_like_file_output(channels))
        return blender_spec("", true);
      return blender_spec(view_layer.empty() ? pick_view_layer(channels, file) : view_layer, false);
    case Layout::aov: return aov_spec();
    case Layout::custom: return custom_spec();
    case Layout::automatic: break;
  }
  throw std::logic_error("layout_spec: auto is not a layout; call detect_layout");
}

LayoutSpec detect_layout(const std::vector<std::string>& channels, const ReadOptions& options,
                         const std::filesystem::path& file) {
  if (!options.view_layer.empty() || !blender_layers(channels).empty() || looks_like_file_output(channels))
    return layout_spec(Layout::blender, options.view_layer, channels, file);
  if (looks_like_aov(channels)) return aov_spec();
  if (has(channels, "material") || options.channels.empty()) return phongcl_spec();
  return custom_spec();
}

}  // namespace phongcl
