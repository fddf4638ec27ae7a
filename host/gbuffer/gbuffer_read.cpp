// Reading a G-buffer EXR in any layout into planes: resolve the layout's channels against the
// file, report everything missing at once, then read and mark background.
#include <algorithm>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/joined.h"
#include "common/memory_limit.h"
#include "exr/exr_channels.h"
#include "gbuffer/edge_policy.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/layout_presets.h"
#include "gbuffer/layouts.h"

namespace phongcl {

namespace {

std::size_t present_count(const PassSource& source, const exr::InputExr& input) {
  return static_cast<std::size_t>(std::count_if(source.channels.begin(), source.channels.end(),
                                                [&](const std::string& name) { return input.has_channel(name); }));
}

bool complete(const PassSource* source, const exr::InputExr& input) {
  return source != nullptr && present_count(*source, input) == source->channels.size();
}

// The first source whose channels are all present, else the most complete one (to name what is
// missing); null if the layout has no source for the pass.
const PassSource* best_source(const PassSpec& spec, const exr::InputExr& input) {
  const PassSource* best = nullptr;
  for (const auto& source : spec.sources) {
    if (complete(&source, input)) return &source;
    if (best == nullptr || present_count(source, input) > present_count(*best, input)) best = &source;
  }
  return best;
}

// The layout's passes matched against the file, with the user's mapping on top.
struct Resolution {
  ChannelMap channels;
  std::vector<std::string> labels;  // of the passes used, in the layout's order
  std::map<Pass, std::string> label_of;  // of each pass used
  std::vector<std::string> unused;       // colour passes present but not used: "GlossCol not used as ks"
  std::vector<std::string> missing_required, missing_from_partial_group;
};

ColourSource colour_choice(Pass pass, const ReadOptions& options) {
  if (pass == Pass::kd) return options.kd;
  if (pass == Pass::ks) return options.ks;
  return ColourSource::layout_default;
}

Resolution resolve(const LayoutSpec& spec, const ReadOptions& options, const exr::InputExr& input,
                   const std::filesystem::path& file, const std::string& found) {
  const ChannelMap& user = options.channels;
  for (const auto& [pass, channels] : user)
    for (const auto& name : channels)
      if (!input.has_channel(name))
        throw InputError(file, "--channel " + std::string(pass_name(pass)) + ": no channel '" + name + "'" + found);
  const auto user_label = [](Pass pass, const std::vector<std::string>& channels) {
    return std::string(pass_name(pass)) + "=" + joined(channels, ",", "none");
  };
  // A depth the user names (and no position) is a request to reconstruct positions from it.
  const bool depth_stands_in = user.count(Pass::depth) > 0 && user.count(Pass::position) == 0;
  bool depth_available = user.count(Pass::depth) > 0;
  for (const auto& pass_spec : spec.passes)
    if (pass_spec.pass == Pass::depth) depth_available |= complete(best_source(pass_spec, input), input);

  Resolution r;
  for (const auto& pass_spec : spec.passes) {
    const Pass pass = pass_spec.pass;
    if (depth_stands_in && pass == Pass::position) continue;
    if (const auto mapped = user.find(pass); mapped != user.end()) {
      r.channels[pass] = mapped->second;
      r.labels.push_back(user_label(pass, mapped->second));
      continue;
    }
    const PassSource* source = best_source(pass_spec, input);
    const ColourSource choice = colour_choice(pass, options);
    const bool wanted = choice == ColourSource::pass || (choice == ColourSource::layout_default && pass_spec.used_by_default);
    if (choice == ColourSource::pass && (source == nullptr || present_count(*source, input) == 0))
      throw InputError(file, "--" + std::string(pass_name(pass)) + "-from pass: the file has no " + pass_name(pass) + " pass" + found);
    if (!wanted) {
      if (complete(source, input))
        r.unused.push_back(source->label + " not used as " + pass_name(pass) + " (--" + pass_name(pass) + "-from pass uses it)");
      continue;
    }
    if (complete(source, input)) {
      r.channels[pass] = source->channels;
      r.labels.push_back(source->label);
      r.label_of[pass] = source->label;
      continue;
    }
    const bool required = pass_spec.required && !(pass == Pass::position && depth_available);
    if (source == nullptr) {
      if (required) r.missing_required.push_back(std::string(pass_name(pass)) + " (give --channel " + pass_name(pass) + "=...)");
      continue;
    }
    if (!required && present_count(*source, input) == 0) continue;  // an absent optional pass
    auto& list = required ? r.missing_required : r.missing_from_partial_group;
    for (const auto& name : source->channels)
      if (!input.has_channel(name)) list.push_back(name);
  }
  for (const auto& [pass, channels] : user)  // passes the layout does not list
    if (!r.channels.count(pass)) {
      r.channels[pass] = channels;
      r.labels.push_back(user_label(pass, channels));
    }
  return r;
}

std::string describe(const LayoutSpec& spec, const Resolution& r) {
  std::string text = layout_name(spec.layout);
  text += " (";
  if (spec.file_output) text += "File Output node: ";
  else if (spec.layout == Layout::blender) text += "view layer '" + spec.view_layer + "': ";
  text += joined(r.labels, ", ", "none");
  if (!r.channels.count(Pass::material)) text += "; no material pass: material 0";
  if (!r.channels.count(Pass::position)) text += "; positions from depth";
  // Where the file has colour passes, say which became kd and ks.
  if (spec.layout != Layout::phongcl && (r.channels.count(Pass::kd) || r.channels.count(Pass::ks) || !r.unused.empty())) {
    const auto from = [&](Pass pass) {
      const auto label = r.label_of.find(pass);
      return label != r.label_of.end() ? label->second : r.channels.count(pass) ? "--channel" : "the scene's table";
    };
    text += "; kd from " + from(Pass::kd) + ", ks from " + from(Pass::ks);
  }
  for (const auto& unused : r.unused) text += "; " + unused;
  return text + ")";
}

// Every shaded pixel at material 0 while the file has a material pass: Blender's pass indices
// were most likely never set, and the sky has index 0 too.
bool every_surface_is_material_zero(const GBuffer& g) {
  bool any_surface = false;
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    if (g.material[i] < 0.0f) continue;
    if (g.material[i] != 0.0f) return false;
    any_surface = true;
  }
  return any_surface;
}

// Where each pass's channels go: the G-buffer's planes, or the reader's own for depth and alpha.
std::vector<Plane*> destinations(Pass pass, GBufferRead& read, Plane& alpha) {
  GBuffer& g = read.gbuffer;
  const auto three = [](Planes3& planes) { return std::vector<Plane*>{&planes[0], &planes[1], &planes[2]}; };
  switch (pass) {
    case Pass::position: return three(g.position);
    case Pass::normal: return three(g.normal);
    case Pass::ka: return three(g.ka);
    case Pass::kd: return three(g.kd);
    case Pass::ks: return three(g.ks);
    case Pass::material: return {&g.material};
    case Pass::shininess: return {&g.shininess};
    case Pass::depth: return {&read.depth};
    case Pass::alpha: return {&alpha};
  }
  return {};
}

void mark_background(GBuffer& g, const Plane& alpha, bool zero_normal_is_background) {
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    const bool uncovered = !alpha.empty() && alpha[i] == 0.0f;
    const bool no_normal =
        zero_normal_is_background && g.normal[0][i] == 0.0f && g.normal[1][i] == 0.0f && g.normal[2][i] == 0.0f;
    if (uncovered || no_normal) g.material[i] = -1.0f;
  }
}

// Every plane at once, so that a window too large for this machine is one line naming the file
// and the size rather than std::bad_alloc.
void allocate_planes(const std::vector<Plane*>& planes, const GBuffer& g, const std::filesystem::path& file) {
  try {
    for (Plane* plane : planes) plane->assign(g.pixel_count(), 0.0f);
  } catch (const std::bad_alloc&) {
    const double bytes = static_cast<double>(planes.size() * g.pixel_count() * sizeof(float));
    throw InputError(file, "cannot allocate " + format_bytes(bytes) + " for " + std::to_string(planes.size()) +
                               " planes of " + std::to_string(g.width) + "x" + std::to_string(g.height) + " pixels");
  }
}

}  // namespace

GBufferRead read_gbuffer(const std::filesystem::path& file, const ReadOptions& options) {
  exr::InputExr input(file, options.max_pixels);
  const std::vector<std::string> channel_names = input.channel_names();
  const LayoutSpec spec = options.layout == Layout::automatic
                              ? detect_layout(channel_names, options, file)
                              : layout_spec(options.layout, options.view_layer, channel_names, file);
  const std::string context = spec.layout == Layout::phongcl ? "" : std::string(layout_name(spec.layout)) + " layout; ";
  const std::string found = " (" + context + "found: " + joined(channel_names, ", ", "none") + ")";

  // Every problem with the channel list is reported before any pixel is read.
  const Resolution r = resolve(spec, options, input, file, found);
  if (!r.missing_required.empty())
    throw InputError(file, (r.missing_required.size() == 1 ? "missing channel " : "missing channels ") +
                               joined(r.missing_required, ", ", "none") + found);
  if (!r.missing_from_partial_group.empty())
    throw InputError(file, "incomplete per-pixel material group, missing " + joined(r.missing_from_partial_group, ", ", "none") + found);

  GBufferRead read;
  read.layout = spec.layout;
  read.description = describe(spec, r);
  read.depth_convention = options.depth_convention.value_or(spec.depth_convention);
  read.depth_convention_reason = options.depth_convention ? "as --depth-convention says" : spec.depth_reason;
  GBuffer& g = read.gbuffer;
  g.source = file;
  g.data_window = input.data_window();
  g.display_window = input.display_window();
  g.compression = input.compression();
  g.width = g.data_window.width();
  g.height = g.data_window.height();

  Plane alpha;
  std::vector<exr::ReadSlice> slices;
  std::vector<Plane*> planes;
  for (const auto& [pass, channels] : r.channels) {
    // Depth is read even beside a position pass: it tells the renderer's sky samples (edge_policy.h).
    const auto pass_planes = destinations(pass, read, alpha);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      planes.push_back(pass_planes[c]);
      slices.push_back({channels[c], nullptr});
    }
  }
  // The renderer's own image rides along when present: no pass depends on it.
  const auto beauty = std::find_if(spec.beauty.begin(), spec.beauty.end(),
                                   [&](const PassSource& source) { return complete(&source, input); });
  if (options.beauty && beauty != spec.beauty.end()) {
    read.beauty = beauty->label;
    for (std::size_t c = 0; c < 3; ++c) {
      planes.push_back(&g.beauty[c]);
      slices.push_back({beauty->channels[c], nullptr});
    }
  }
  const bool material_read = r.channels.count(Pass::material) > 0;
  if (!material_read) planes.push_back(&g.material);  // zeros: material 0
  allocate_planes(planes, g, file);
  for (std::size_t i = 0; i < slices.size(); ++i) slices[i].first = planes[i]->data();
  input.read(slices);
  mark_background(g, alpha, spec.zero_normal_is_background);
  if (spec.zero_normal_is_background) {  // a renderer's file: its edges (gbuffer/edge_policy.h)
    const std::size_t sky = mark_sky_samples(g, read.depth, spec.no_hit_depth);
    if (sky > 0) read.description += ", " + std::to_string(sky) + " sky samples with a filtered normal as background";
    const CoverageSource coverage = estimate_coverage(g, alpha);
    if (coverage != CoverageSource::none) read.description += std::string(", coverage from ") + coverage_source_name(coverage);
    read.edges_need_positions = read.needs_positions_from_depth();
    if (!read.edges_need_positions) repair_edges(read);
  }
  if (material_read && every_surface_is_material_zero(g))
    read.warnings.push_back("every surface pixel has material index 0: pass indices were probably never set (in "
                            "Blender: each material's Pass Index), so every surface gets material 0's ka, kd, ks and "
                            "shininess");
  return read;
}

void repair_edges(GBufferRead& read) {
  read.edges_need_positions = false;
  const std::size_t repaired = repair_surface_edges(read.gbuffer);
  if (repaired > 0) read.description += ", " + std::to_string(repaired) + " edge pixels between surfaces given their centre surface's normal";
}

GBuffer read_gbuffer(const std::filesystem::path& file) { return read_gbuffer(file, ReadOptions{}).gbuffer; }

}  // namespace phongcl
