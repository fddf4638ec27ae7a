#include "serve/api_routes.h"

#include <chrono>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "scene/json_reader.h"
#include "serve/image_encoding.h"
#include "serve/query.h"

namespace phongcl {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// The first frame can include a kernel build of several seconds on a busy machine.
constexpr std::chrono::seconds kFrameTimeout{120};
constexpr long long kMaxPollMs = 60'000;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

void send_json(httplib::Response& response, const json& body, int status = 200) {
  response.status = status;
  response.set_content(body.dump() + "\n", "application/json");
}

ToneMap parse_tone_map(const std::string& name) {
  if (name == "clamp") return ToneMap::clamp;
  if (name == "reinhard") return ToneMap::reinhard;
  if (name == "aces") return ToneMap::aces;
  throw BadRequest("parameter 'tonemap' must be clamp, reinhard or aces (got '" + name + "')");
}

// Which image of a frame a request shows.
enum class Term { combined, ambient, diffuse, specular };
Term parse_term(const std::string& name) {
  if (name == "combined") return Term::combined;
  if (name == "ambient") return Term::ambient;
  if (name == "diffuse") return Term::diffuse;
  if (name == "specular") return Term::specular;
  throw BadRequest("parameter 'aov' must be combined, ambient, diffuse or specular (got '" + name + "')");
}

const Image& term_image(const Frame& frame, Term term) {
  switch (term) {
    case Term::ambient: return frame.terms.ambient;
    case Term::diffuse: return frame.terms.diffuse;
    case Term::specular: return frame.terms.specular;
    case Term::combined: break;
  }
  return frame.image;
}

const std::vector<std::string_view> kBeautyParameters{"format", "width", "exposure", "tonemap"};
const std::vector<std::string_view> kImageParameters{"format", "width", "exposure", "tonemap", "aov"};
const std::vector<std::string_view> kPollParameters{"format", "width", "exposure", "tonemap", "aov", "after", "timeout_ms"};

Term requested_term(const Query& query) { return parse_term(query.text("aov").value_or("combined")); }

json timings_json(const FrameTimings& t) {
  return {{"build_ms", t.build_ms}, {"kernel_ms", t.kernel_ms}, {"transfer_ms", t.transfer_ms}, {"shade_ms", t.shade_ms}};
}

json vec3_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

RenderSettings parse_settings(const std::string& body, RenderSettings settings) {
  json document;
  try {
    document = json::parse(body);
  } catch (const json::exception& error) {
    throw BadRequest(std::string("settings: invalid JSON: ") + error.what());
  }
  const std::filesystem::path source = "settings";
  const JsonObject object = JsonValue(document, "", source).object();
  object.expect_keys({"precision", "specialise", "shadows", "shadow_steps", "shadow_thickness"});
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
  try {
    if (auto value = object.find("shadows")) settings.shadows.mode = parse_shadow_mode(value->string());
    if (auto value = object.find("shadow_steps")) settings.shadows.steps = value->integer();
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
          {"shadow_thickness", format_shadow_thickness(settings.shadows.thickness)}};
}

}  // namespace

std::string error_json(const std::string& message) { return json{{"error", message}}.dump() + "\n"; }

void ApiRoutes::add_to(httplib::Server& server) {
  auto route = [this](void (ApiRoutes::*handler)(const httplib::Request&, httplib::Response&)) {
    return [this, handler](const httplib::Request& request, httplib::Response& response) {
      try {
        (this->*handler)(request, response);
      } catch (const BadRequest& error) {
        send_json(response, {{"error", error.what()}}, 400);
      } catch (const InputError& error) {
        send_json(response, {{"error", error.what()}}, 400);
      }
    };
  };
  server.Get("/api/scene", route(&ApiRoutes::get_scene));
  server.Put("/api/scene", route(&ApiRoutes::put_scene));
  server.Get("/api/settings", route(&ApiRoutes::get_settings));
  server.Put("/api/settings", route(&ApiRoutes::put_settings));
  server.Get("/api/image", route(&ApiRoutes::get_image));
  server.Get("/api/frame", route(&ApiRoutes::get_frame));
  server.Get("/api/stats", route(&ApiRoutes::get_stats));
  server.Get("/api/pick", route(&ApiRoutes::get_pick));
  server.Post("/api/save", route(&ApiRoutes::post_save));
  server.Get("/api/beauty", route(&ApiRoutes::get_beauty));
}

void ApiRoutes::get_scene(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  const SceneSnapshot scene = live_.scene();
  response.set_header("X-Scene-Version", std::to_string(scene.scene_version));
  response.set_content(scene.json, "application/json");
}

void ApiRoutes::put_scene(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  const std::uint64_t version = live_.replace_scene(request.body);
  send_json(response, {{"scene_version", version}});
}

void ApiRoutes::get_settings(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  send_json(response, settings_json(live_.settings()));
}

void ApiRoutes::put_settings(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  const RenderSettings settings = parse_settings(request.body, live_.settings());
  live_.replace_settings(settings);
  send_json(response, settings_json(settings));
}

void ApiRoutes::get_image(const httplib::Request& request, httplib::Response& response) {
  const Query query(request, kImageParameters);
  const auto frame = live_.current_frame(requested_term(query) != Term::combined, kFrameTimeout);
  if (!frame) return send_json(response, {{"error", "no frame within the time limit (server busy or stopping)"}}, 503);
  send_frame(query, *frame, response);
}

void ApiRoutes::get_frame(const httplib::Request& request, httplib::Response& response) {
  const Query query(request, kPollParameters);
  const auto after = static_cast<std::uint64_t>(query.integer("after", 0, std::numeric_limits<long long>::max(), 0));
  const auto timeout = std::chrono::milliseconds(query.integer("timeout_ms", 0, kMaxPollMs, 20'000));
  const auto frame = live_.wait_for_frame(after, requested_term(query) != Term::combined, timeout);
  if (!frame) {
    response.status = 204;  // nothing newer yet: poll again
    return;
  }
  send_frame(query, *frame, response);
}

void ApiRoutes::get_beauty(const httplib::Request& request, httplib::Response& response) {
  const Query query(request, kBeautyParameters);
  const Image* beauty = live_.session().beauty();
  if (!beauty)
    return send_json(response, {{"error", "the G-buffer file has no beauty pass (the renderer's own image, e.g. Blender's Combined)"}}, 404);
  send_image(query, *beauty, response);
}

void ApiRoutes::send_frame(const Query& query, const RenderedFrame& frame, httplib::Response& response) {
  const Term term = requested_term(query);
  response.set_header("X-Frame-Version", std::to_string(frame.version));
  response.set_header("X-Scene-Version", std::to_string(frame.scene_version));
  if (!frame.error.empty()) return send_json(response, {{"error", frame.error}}, 422);
  response.set_header("X-Shade-Ms", format_number(frame.frame.timings.shade_ms));
  response.set_header("X-Kernel-Ms", format_number(frame.frame.timings.kernel_ms));
  send_image(query, term_image(frame.frame, term), response);
}

// The image in the query's format, display settings and width.
void ApiRoutes::send_image(const Query& query, const Image& image, httplib::Response& response) {
  const std::string format_name = query.text("format").value_or("png");
  ImageFormat format;
  try {
    format = parse_image_format(format_name);
  } catch (const std::invalid_argument& error) {
    throw BadRequest(std::string("parameter 'format': ") + error.what());
  }
  DisplaySettings display;
  display.exposure_stops = query.number("exposure", -40.0, 40.0, 0.0);
  display.tone_map = parse_tone_map(query.text("tonemap").value_or("reinhard"));
  const int width = static_cast<int>(query.integer("width", 1, image.width, image.width));
  const Clock::time_point start = Clock::now();
  const std::string bytes = width == image.width ? encode_image(image, format, display)
                                                 : encode_image(scale_to_width(image, width), format, display);
  const double encode_ms = elapsed_ms(start);
  {
    std::lock_guard lock(encode_mutex_);
    last_encode_ms_[format_name] = encode_ms;
  }
  response.set_header("X-Encode-Ms", format_number(encode_ms));
  response.set_header("Cache-Control", "no-store");
  response.set_content(bytes, content_type(format));
}

void ApiRoutes::get_stats(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  const auto frame = live_.latest_frame();
  const RenderCounters counters = live_.counters();
  json stats{{"width", live_.session().width()},
             {"height", live_.session().height()},
             {"device", options_.device},
             {"settings", settings_json(live_.settings())},
             {"scene_version", live_.scene().scene_version},
             {"frames", counters.frames},
             {"shade_fps", counters.frames_per_second},
             {"save_path", options_.save_path.string()},
             {"beauty", live_.session().beauty() != nullptr}};
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
  std::lock_guard lock(encode_mutex_);
  stats["encode_ms"] = last_encode_ms_;
  send_json(response, stats);
}

void ApiRoutes::get_pick(const httplib::Request& request, httplib::Response& response) {
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

void ApiRoutes::post_save(const httplib::Request& request, httplib::Response& response) {
  Query query(request, {});
  if (options_.save_path.empty())
    return send_json(response, {{"error", "no --save path: start phongcl serve with --save FILE to save on the server"}}, 409);
  const SceneSnapshot scene = live_.scene();
  write_atomically(options_.save_path, [&](const std::filesystem::path& temp) {
    std::ofstream stream(temp, std::ios::binary);
    stream << scene.json;
    stream.close();
    if (!stream) throw InputError(options_.save_path, "cannot write");
  });
  send_json(response, {{"saved", options_.save_path.string()}, {"bytes", scene.json.size()}, {"scene_version", scene.scene_version}});
}

}  // namespace phongcl
