#include "serve/api_routes.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "color/color_conversion.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/joined.h"
#include "common/same_file.h"
#include "scene/json_reader.h"
#include "scene/mesh_files.h"
#include "scene/scene_check.h"
#include "serve/image_encoding.h"
#include "serve/query.h"

namespace phongcl {

// Which image of a frame a request shows: the combined image, a term, or a light group's layer. Not in
// the anonymous namespace: ImageRequest, declared in the header, holds one.
struct Term {
  enum class Kind { combined, ambient, diffuse, specular, group } kind = Kind::combined;
  std::string group{};  // Kind::group: its name
  bool needs_terms() const { return kind != Kind::combined; }
};

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

// Text from requests and files (paths, parameter names) may be any bytes: invalid UTF-8 becomes
// U+FFFD rather than an exception from nlohmann.
std::string json_text(const json& body) { return body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n"; }

void send_json(HttpResponse& response, const json& body, int status = 200) {
  response.status = status;
  response.set_content(json_text(body), "application/json");
}

Term parse_term(const std::string& name) {
  if (name == "combined") return {Term::Kind::combined};
  if (name == "ambient") return {Term::Kind::ambient};
  if (name == "diffuse") return {Term::Kind::diffuse};
  if (name == "specular") return {Term::Kind::specular};
  const std::string prefix = "group.";
  if (name.starts_with(prefix) && valid_light_group_name(name.substr(prefix.size())))
    return {Term::Kind::group, name.substr(prefix.size())};
  throw BadRequest("parameter 'aov' must be combined, ambient, diffuse, specular or group.<name> (got '" + name + "')");
}

const Image& term_image(const Frame& frame, const Term& term) {
  switch (term.kind) {
    case Term::Kind::ambient: return frame.terms.ambient;
    case Term::Kind::diffuse: return frame.terms.diffuse;
    case Term::Kind::specular: return frame.terms.specular;
    case Term::Kind::group: {
      const std::vector<std::string>& names = frame.terms.group_names;
      const auto found = std::find(names.begin(), names.end(), term.group);
      if (found == names.end()) throw BadRequest("parameter 'aov': the scene has no light group '" + term.group + "'");
      return frame.terms.groups[static_cast<std::size_t>(found - names.begin())];
    }
    case Term::Kind::combined: break;
  }
  return frame.image;
}

// The display parameters (color/display.h); tonemap is view's name from before OCIO.
const std::vector<std::string_view> kBeautyParameters{"format", "width", "exposure", "display", "view", "look", "tonemap"};
const std::vector<std::string_view> kImageParameters{"format", "width", "exposure", "display", "view", "look", "tonemap", "aov"};
const std::vector<std::string_view> kPollParameters{"format", "width", "exposure", "display", "view", "look", "tonemap",
                                                    "aov", "after", "timeout_ms"};

}  // namespace

// What a request asks of an image, read whole from its query before it waits for a frame.
struct ImageRequest {
  std::string format_name;
  ImageFormat format;
  DisplaySettings display;
  int width;
  Term term;
};

namespace {

// The names are checked against `color` here (a 400 listing what the config has), before the
// request waits for a frame; the background is each frame's.
ImageRequest image_request(const Query& query, int image_width, const ColorConfig& color) {
  ImageRequest wanted;
  wanted.format_name = query.text("format").value_or("png");
  try {
    wanted.format = parse_image_format(wanted.format_name);
  } catch (const std::invalid_argument& error) {
    throw BadRequest(std::string("parameter 'format': ") + error.what());
  }
  DisplaySettings& display = wanted.display;
  display.exposure_stops = query.number("exposure", -kMaxExposureStops, kMaxExposureStops, 0.0);
  display.display = query.text("display").value_or("");
  display.view = query.text("view").value_or("");
  if (const auto tonemap = query.text("tonemap")) {
    if (!display.view.empty()) throw BadRequest("parameters 'view' and 'tonemap' (its old name) name the same thing: give one");
    display.view = *tonemap;
  }
  display.look = query.text("look").value_or("");
  DisplayTransform(color, display);  // for EXR too: a name the config lacks is an error whatever the format
  wanted.width = static_cast<int>(query.integer("width", 1, image_width, image_width));
  wanted.term = parse_term(query.text("aov").value_or("combined"));
  return wanted;
}

json timings_json(const FrameTimings& t) {
  return {{"build_ms", t.build_ms}, {"kernel_ms", t.kernel_ms}, {"transfer_ms", t.transfer_ms}, {"shade_ms", t.shade_ms}};
}

json vec3_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

// The render frames are composited over, and what the frame did with each of its light groups.
json over_json(const RenderCompositor& over, const std::optional<OverGroups>& frame_groups) {
  const RenderPasses& passes = over.passes();
  json groups = json::array();
  for (const GroupEdit& edit : frame_groups ? frame_groups->edits : std::vector<GroupEdit>{}) {
    json group{{"name", edit.group}, {"change", to_string(edit.change)}, {"pass", passes.group_passes.count(edit.group) > 0}};
    if (edit.change == GroupChange::scaled) group["scale"] = vec3_json(edit.scale);
    if (const auto fit = frame_groups->fits.find(edit.group); fit != frame_groups->fits.end())
      group["fit"] = {{"diffuse_gain", vec3_json(fit->second.diffuse_gain)},
                      {"specular_gain", vec3_json(fit->second.specular_gain)},
                      {"residual", fit->second.residual}};
    groups.push_back(group);
  }
  json pass_names = json::array();
  for (const auto& [name, pass] : passes.group_passes) pass_names.push_back(name);
  return {{"render", over.file().string()},
          {"view_layer", passes.layer.empty() ? "" : passes.layer.substr(0, passes.layer.size() - 1)},
          {"passes", pass_names},
          {"groups", groups}};
}

// "r,g,b": three finite numbers.
glm::dvec3 parse_rgb(const std::string& text) {
  glm::dvec3 rgb;
  std::size_t at = 0;
  for (int c = 0; c < 3; ++c) {
    const std::size_t end = c < 2 ? text.find(',', at) : text.size();
    const std::string part = end == std::string::npos ? "" : text.substr(at, end - at);
    char* stop = nullptr;
    rgb[c] = std::strtod(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || !std::isfinite(rgb[c]))
      throw BadRequest("parameter 'rgb' must be three finite numbers r,g,b (got '" + text + "')");
    at = end + 1;
  }
  return rgb;
}

// `groups`: the scene's light groups, which solo must name (as aov= must): soloing a group the
// scene lacks would darken every light.
RenderSettings parse_settings(const std::string& body, RenderSettings settings, const std::vector<std::string>& groups) {
  const std::filesystem::path source = "settings";
  const json document = parse_json(body, source);
  const JsonObject object = JsonValue(document, "", source).object();
  object.expect_keys({"precision", "specialise", "shadows", "shadow_steps", "shadow_thickness", "shadow_rays", "solo",
                      "mute"});
  if (auto value = object.find("precision")) {
    try {
      settings.precision = parse_precision(value->string());
    } catch (const std::invalid_argument& error) {
      value->fail(error.what());
    }
  }
  if (auto value = object.find("specialise")) {
    if (!value->json().is_boolean()) value->fail("must be true or false");
    settings.specialise = value->json().get<bool>();
  }
  if (auto value = object.find("solo")) {
    settings.solo = value->string();
    if (!settings.solo.empty() && !valid_light_group_name(settings.solo)) value->fail(kLightGroupNameRule);
    if (!settings.solo.empty() && std::find(groups.begin(), groups.end(), settings.solo) == groups.end())
      value->fail("the scene has no light group '" + settings.solo + "' (groups: " + joined(groups, ", ", "none") + ")");
  }
  if (auto value = object.find("mute")) {
    settings.muted.clear();
    for (const JsonValue& group : value->elements()) {
      settings.muted.push_back(group.string());
      if (!valid_light_group_name(settings.muted.back())) group.fail(kLightGroupNameRule);
    }
  }
  try {
    if (auto value = object.find("shadows")) settings.shadows.mode = parse_shadow_mode(value->string());
    if (auto value = object.find("shadow_steps")) settings.shadows.steps = value->integer();
    if (auto value = object.find("shadow_rays")) settings.shadows.rays = value->integer();
    if (auto value = object.find("shadow_thickness"))
      settings.shadows.thickness = parse_shadow_thickness(value->string());
    check_shadow_settings(settings.shadows);
  } catch (const std::invalid_argument& error) {
    throw BadRequest(std::string("settings: ") + error.what());
  }
  return settings;
}

json settings_json(const RenderSettings& settings) {
  return {{"precision", to_string(settings.precision)},
          {"specialise", settings.specialise},
          {"shadows", to_string(settings.shadows.mode)},
          {"shadow_steps", settings.shadows.steps},
          {"shadow_thickness", format_shadow_thickness(settings.shadows.thickness)},
          {"shadow_rays", settings.shadows.rays},
          {"solo", settings.solo},
          {"mute", settings.muted}};
}

}  // namespace

void ApiRoutes::add_to(HttpRouter& router) {
  auto route = [this](void (ApiRoutes::*handler)(const HttpRequest&, HttpResponse&)) {
    return [this, handler](const HttpRequest& request, HttpResponse& response) {
      // Nothing leaves a handler: whatever a request sends, the server answers it and goes on.
      try {
        (this->*handler)(request, response);
      } catch (const BadRequest& error) {
        send_json(response, {{"error", error.what()}}, 400);
      } catch (const InputError& error) {
        send_json(response, {{"error", error.what()}}, 400);
      } catch (const Unavailable& error) {
        response.set_header("Retry-After", "1");
        send_json(response, {{"error", error.what()}}, 503);
      } catch (const ServerError& error) {
        send_json(response, {{"error", error.what()}}, 500);
      } catch (const std::exception& error) {
        send_json(response, {{"error", std::string("internal error: ") + error.what()}}, 500);
      } catch (...) {
        send_json(response, {{"error", "internal error"}}, 500);
      }
    };
  };
  router.add("GET", "/api/scene", route(&ApiRoutes::get_scene));
  router.add("PUT", "/api/scene", route(&ApiRoutes::put_scene));
  router.add("GET", "/api/settings", route(&ApiRoutes::get_settings));
  router.add("PUT", "/api/settings", route(&ApiRoutes::put_settings));
  router.add("GET", "/api/image", route(&ApiRoutes::get_image));
  router.add("GET", "/api/frame", route(&ApiRoutes::get_frame));
  router.add("GET", "/api/stats", route(&ApiRoutes::get_stats));
  router.add("GET", "/api/pick", route(&ApiRoutes::get_pick));
  router.add("POST", "/api/save", route(&ApiRoutes::post_save));
  router.add("GET", "/api/beauty", route(&ApiRoutes::get_beauty));
  router.add("GET", "/api/colors", route(&ApiRoutes::get_colors));
  router.add("GET", "/api/color", route(&ApiRoutes::get_color));
}

void ApiRoutes::get_scene(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  const SceneSnapshot scene = live_.scene();
  response.set_header("X-Scene-Version", std::to_string(scene.scene_version));
  response.set_content(scene.json, "application/json");
}

void ApiRoutes::put_scene(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  const std::uint64_t version = live_.replace_scene(request.body);
  send_json(response, {{"scene_version", version}});
}

void ApiRoutes::get_settings(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  send_json(response, settings_json(live_.settings()));
}

void ApiRoutes::put_settings(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  const RenderSettings settings = parse_settings(request.body, live_.settings(), live_.scene().light_groups);
  live_.replace_settings(settings);
  send_json(response, settings_json(settings));
}

ApiRoutes::WaitingPlace::WaitingPlace(ApiRoutes& routes) : routes_(routes) {
  std::lock_guard lock(routes_.waiting_mutex_);
  const std::size_t limit = routes_.options_.limits.max_waiting;
  if (routes_.waiting_ >= limit)
    throw Unavailable("too many requests waiting for frames (" + std::to_string(limit) + "): try again");
  ++routes_.waiting_;
}

ApiRoutes::WaitingPlace::~WaitingPlace() {
  std::lock_guard lock(routes_.waiting_mutex_);
  --routes_.waiting_;
}

void ApiRoutes::get_image(const HttpRequest& request, HttpResponse& response) {
  const ImageRequest wanted = image_request(Query(request, kImageParameters), live_.session().width(), live_.color_config());
  const WaitingPlace place(*this);
  const auto frame = live_.current_frame(wanted.term.needs_terms(), options_.frame_timeout);
  if (!frame) return send_json(response, {{"error", "no frame within the time limit (server busy or stopping)"}}, 503);
  send_frame(wanted, *frame, response);
}

void ApiRoutes::get_frame(const HttpRequest& request, HttpResponse& response) {
  const Query query(request, kPollParameters);
  const ImageRequest wanted = image_request(query, live_.session().width(), live_.color_config());
  const auto after = static_cast<std::uint64_t>(query.integer("after", 0, std::numeric_limits<long long>::max(), 0));
  const auto timeout = std::chrono::milliseconds(
      query.integer("timeout_ms", 0, options_.max_poll.count(), std::min<long long>(20'000, options_.max_poll.count())));
  const WaitingPlace place(*this);
  const auto frame = live_.wait_for_frame(after, wanted.term.needs_terms(), timeout);
  if (!frame) {
    response.status = 204;  // nothing newer yet: poll again
    return;
  }
  send_frame(wanted, *frame, response);
}

void ApiRoutes::get_beauty(const HttpRequest& request, HttpResponse& response) {
  const ImageRequest wanted = image_request(Query(request, kBeautyParameters), live_.session().width(), live_.color_config());
  const Image* beauty = live_.session().beauty();
  if (!beauty)
    return send_json(response, {{"error", "the G-buffer file has no beauty pass (the renderer's own image, e.g. Blender's Combined)"}}, 404);
  send_image(wanted, *beauty, glm::dvec3(0.0), response);  // opaque: nothing shows through
}

void ApiRoutes::send_frame(const ImageRequest& wanted, const RenderedFrame& frame, HttpResponse& response) {
  response.set_header("X-Frame-Version", std::to_string(frame.version));
  response.set_header("X-Scene-Version", std::to_string(frame.scene_version));
  if (!frame.error.empty()) return send_json(response, {{"error", frame.error}}, 422);
  response.set_header("X-Shade-Ms", format_number(frame.frame.timings.shade_ms));
  response.set_header("X-Kernel-Ms", format_number(frame.frame.timings.kernel_ms));
  send_image(wanted, term_image(frame.frame, wanted.term), frame.background, response);
}

// The image in the request's format, display settings and width, over `background`.
void ApiRoutes::send_image(const ImageRequest& wanted, const Image& image, const glm::dvec3& background,
                           HttpResponse& response) {
  const ColorConfig& color = live_.color_config();
  DisplaySettings settings = wanted.display;
  settings.background = background;
  const DisplayTransform display(color, settings);
  const Clock::time_point start = Clock::now();
  std::optional<Image> resized;
  if (wanted.width != image.width) resized = scale_to_width(image, wanted.width);
  const Image& scaled = resized ? *resized : image;
  // EXR: RGB 0 where alpha is 0, the working space's chromaticities when known.
  const std::string bytes = wanted.format == ImageFormat::exr
                                ? encode_exr(scaled, {.chromaticities = color.working_chromaticities()})
                                : encode_display_image(scaled, wanted.format, display);
  const double encode_ms = elapsed_ms(start);
  {
    std::lock_guard lock(encode_mutex_);
    last_encode_ms_[wanted.format_name] = encode_ms;
  }
  response.set_header("X-Encode-Ms", format_number(encode_ms));
  response.set_header("Cache-Control", "no-store");
  response.set_content(bytes, content_type(wanted.format));
}

void ApiRoutes::get_stats(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  const auto frame = live_.latest_frame();
  const RenderCounters counters = live_.counters();
  json stats{{"width", live_.session().width()},
             {"height", live_.session().height()},
             {"device", options_.device},
             {"settings", settings_json(live_.settings())},
             {"scene_version", live_.scene().scene_version},
             {"light_groups", live_.scene().light_groups},
             {"frames", counters.frames},
             {"shade_fps", counters.frames_per_second},
             {"save_path", options_.save_path.string()},
             {"beauty", live_.session().beauty() != nullptr}};
  if (const RenderCompositor* over = live_.session().over())
    stats["over"] = over_json(*over, frame ? frame->frame.over : std::nullopt);
  if (frame) {
    stats["frame"] = {{"version", frame->version},
                      {"scene_version", frame->scene_version},
                      {"precision", to_string(frame->settings.precision)},
                      {"kernel", frame->frame.kernel},
                      {"build", frame->frame.build},
                      {"timings", timings_json(frame->frame.timings)},
                      {"warnings", frame->frame.warnings},
                      {"error", frame->error}};
  }
  {
    std::lock_guard lock(waiting_mutex_);
    stats["waiting_for_frames"] = waiting_;
  }
  std::lock_guard lock(encode_mutex_);
  stats["encode_ms"] = last_encode_ms_;
  send_json(response, stats);
}

void ApiRoutes::get_pick(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {"x", "y"});
  if (!query.text("x") || !query.text("y")) throw BadRequest("parameters 'x' and 'y' (pixel, row 0 at the top) are required");
  const RelightSession& session = live_.session();
  const int x = static_cast<int>(query.integer("x", 0, session.width() - 1, 0));
  const int y = static_cast<int>(query.integer("y", 0, session.height() - 1, 0));
  const SurfacePick pick = session.pick(x, y);
  json body{{"x", x}, {"y", y}, {"shaded", pick.shaded}};
  if (pick.shaded) {
    body["position"] = vec3_json(pick.position);
    body["normal"] = vec3_json(pick.normal);
    body["material"] = pick.material;
  }
  send_json(response, body);
}

// The config's displays with their views, its looks and colour spaces, and the colour pickers' space.
void ApiRoutes::get_colors(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  const ColorConfig& color = live_.color_config();
  json displays = json::array();
  for (const std::string& display : color.displays())
    displays.push_back({{"name", display}, {"views", color.views(display)}, {"default_view", color.default_view(display)},
                        {"picker_space", color.picker_space(display)}});
  send_json(response, {{"config", color.description()},
                       {"working_space", color.working_space()},
                       {"default_display", color.default_display()},
                       {"displays", displays},
                       {"looks", color.looks()},
                       {"color_spaces", color.color_spaces()}});
}

// One colour from one of the config's spaces into another: the page's colour pickers show and
// send values through it.
void ApiRoutes::get_color(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {"rgb", "from", "to"});
  const auto rgb = query.text("rgb"), from = query.text("from"), to = query.text("to");
  if (!rgb || !from || !to) throw BadRequest("parameters 'rgb' (r,g,b), 'from' and 'to' (colour spaces) are required");
  const ColorConversion conversion(live_.color_config(), *from, "parameter 'from'/'to'", *to);
  const glm::dvec3 converted = conversion(parse_rgb(*rgb));
  if (!std::isfinite(converted.x) || !std::isfinite(converted.y) || !std::isfinite(converted.z))
    throw BadRequest("parameter 'rgb': '" + *rgb + "' has no finite value in '" + *to + "' (too large to convert)");
  send_json(response, {{"rgb", vec3_json(converted)}});
}

void ApiRoutes::post_save(const HttpRequest& request, HttpResponse& response) {
  Query query(request, {});
  if (options_.save_path.empty())
    return send_json(response, {{"error", "no --save path: start phongcl serve with --save FILE to save on the server"}}, 409);
  const SceneSnapshot scene = live_.scene();
  // A PUT may have named a mesh since start-up, when --save was checked against the inputs.
  std::vector<NamedFile> files{{"--save", options_.save_path, true}};
  for (const std::filesystem::path& mesh : scene.meshes) files.push_back(mesh_input(mesh));
  try {
    refuse_shared_files(files);
  } catch (const std::invalid_argument& error) {
    return send_json(response, {{"error", std::string("save refused: ") + error.what()}}, 409);
  }
  // The request was fine: a failed write is the server's problem (500), with the reason.
  try {
    write_atomically(options_.save_path, [&](const std::filesystem::path& temp) {
      std::ofstream stream(temp, std::ios::binary);
      stream << scene.json;
      stream.close();
      if (!stream) throw InputError(temp, std::string("cannot write: ") + std::strerror(errno));
    });
  } catch (const std::exception& error) {
    throw ServerError(std::string("save failed: ") + error.what());
  }
  send_json(response, {{"saved", options_.save_path.string()}, {"bytes", scene.json.size()}, {"scene_version", scene.scene_version}});
}

}  // namespace phongcl
