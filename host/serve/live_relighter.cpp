#include "serve/live_relighter.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "color/color_conversion.h"
#include "common/error.h"
#include "common/regular_file.h"
#include "scene/mesh_files.h"

namespace phongcl {

namespace {

constexpr std::chrono::seconds kFpsWindow{2};
constexpr std::size_t kLargeSceneBytes = 1u << 20;  // scenes of tens of thousands of materials

// The document is kept as sent (keys this program does not know survive for later readers),
// normalised to one pretty-printed form.
std::string normalised_json(std::string_view text) { return nlohmann::json::parse(text).dump(2) + "\n"; }

// The image of a frame no request holds any more (only the render loop's pointer is left), to
// shade the next frame into; else an empty one. Nobody can take a new reference to a frame that
// latest_ no longer points at, so a count of 1 stays 1; the fence orders the readers' last reads
// before the new writes.
Image reusable_image(std::shared_ptr<RenderedFrame>& retired) {
  Image image;
  if (retired && retired.use_count() == 1) {
    std::atomic_thread_fence(std::memory_order_acquire);
    image = std::move(retired->frame.image);
  }
  retired.reset();
  return image;
}

}  // namespace

LiveRelighter::LiveRelighter(RelightSession& session, std::string_view scene_text, std::filesystem::path scene_source,
                             RenderSettings settings, ColorConfig color)
    : session_(session), scene_source_(std::move(scene_source)), color_(std::move(color)), settings_(settings) {
  scene_ = parsed_scene(scene_text);
  session_.check(scene_);
  scene_json_ = normalised_json(scene_text);
  render_thread_ = std::thread([this] {
    render_loop();
    std::lock_guard lock(mutex_);
    render_thread_done_ = true;
    render_ended_.notify_all();
  });
}

LiveRelighter::~LiveRelighter() {
  stop();
  render_thread_.join();
}

void LiveRelighter::stop() {
  std::lock_guard lock(mutex_);
  stopping_ = true;
  state_changed_.notify_all();
  frame_ready_.notify_all();
}

bool LiveRelighter::render_thread_ended_by(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  return render_ended_.wait_until(lock, deadline, [&] { return render_thread_done_; });
}

SceneSnapshot LiveRelighter::scene() const {
  std::lock_guard lock(mutex_);
  return {scene_version_, scene_json_, light_groups(scene_.lights, scene_.area_lights, scene_.environment), mesh_files(scene_.objects)};
}

// The document as the shader takes it: colours in the working space. A mesh file that cannot be
// opened is refused with it; one that opens but is malformed fails the first frame that reads it
// (meshes are read for shadows traced against the objects), with the reader's error.
Scene LiveRelighter::parsed_scene(std::string_view text) const {
  Scene scene = parse_scene(text, scene_source_);
  for (const std::filesystem::path& mesh : mesh_files(scene.objects)) {
    require_regular_file(mesh, "mesh");
    if (!std::ifstream(mesh, std::ios::binary))
      throw InputError(mesh, std::string("cannot read the mesh: ") + std::strerror(errno));
  }
  convert_scene_colors(scene, color_);
  return scene;
}

std::uint64_t LiveRelighter::replace_scene(std::string_view text) {
  Scene scene = parsed_scene(text);  // outside the lock: a big scene takes a while
  session_.check(scene);
  std::string json = normalised_json(text);
  std::lock_guard lock(mutex_);
  if (scene.gbuffer != scene_.gbuffer)
    throw InputError(scene_source_, "gbuffer: cannot change while serving (the server holds " +
                                        (scene_.gbuffer.empty() ? session_.gbuffer().source : scene_.gbuffer).string() + ")");
  scene_ = std::move(scene);
  scene_json_ = std::move(json);
  ++scene_version_;
  ++version_;
  state_changed_.notify_all();
  return scene_version_;
}

RenderSettings LiveRelighter::settings() const {
  std::lock_guard lock(mutex_);
  return settings_;
}

void LiveRelighter::replace_settings(const RenderSettings& settings) {
  std::lock_guard lock(mutex_);
  settings_ = settings;
  ++version_;
  state_changed_.notify_all();
}

std::shared_ptr<const RenderedFrame> LiveRelighter::wait_locked(std::unique_lock<std::mutex>& lock,
                                                                std::uint64_t min_version, bool need_terms,
                                                                std::chrono::milliseconds timeout) {
  if (need_terms && !terms_wanted_) {
    terms_wanted_ = true;
    ++version_;
    min_version = std::max(min_version, version_);
    state_changed_.notify_all();
  }
  auto ready = [&] {
    return stopping_ || (latest_ && latest_->version >= min_version && (!need_terms || latest_->settings.terms));
  };
  ++waiting_;
  state_changed_.notify_all();
  const bool got = frame_ready_.wait_for(lock, timeout, ready);
  --waiting_;
  if (!got || stopping_) return nullptr;
  if (!latest_taken_) {
    latest_taken_ = true;
    state_changed_.notify_all();
  }
  return latest_;
}

std::shared_ptr<const RenderedFrame> LiveRelighter::wait_for_frame(std::uint64_t after_version, bool need_terms,
                                                                   std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return wait_locked(lock, after_version + 1, need_terms, timeout);
}

std::shared_ptr<const RenderedFrame> LiveRelighter::current_frame(bool need_terms, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return wait_locked(lock, version_, need_terms, timeout);
}

std::shared_ptr<const RenderedFrame> LiveRelighter::latest_frame() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

RenderCounters LiveRelighter::counters() const {
  std::lock_guard lock(mutex_);
  const auto since = std::chrono::steady_clock::now() - kFpsWindow;
  const auto recent = std::count_if(recent_finishes_.begin(), recent_finishes_.end(), [&](auto t) { return t >= since; });
  return {frames_, static_cast<double>(recent) / std::chrono::duration<double>(kFpsWindow).count()};
}

void LiveRelighter::render_loop() {
  std::uint64_t rendered = 0;
  // latest_, and the frame before it, kept for its image: between frames one more image is held,
  // while shading no more than before (the next frame's image is the retired one's).
  std::shared_ptr<RenderedFrame> shown, retired;
  for (;;) {
    auto frame = std::make_shared<RenderedFrame>();
    Scene scene;
    bool large_scene = false;
    {
      std::unique_lock lock(mutex_);
      state_changed_.wait(lock, [&] { return stopping_ || (version_ > rendered && (latest_taken_ || waiting_ > 0)); });
      if (stopping_) return;
      scene = scene_;
      large_scene = scene_json_.size() >= kLargeSceneBytes;
      frame->version = version_;
      frame->scene_version = scene_version_;
      frame->settings = settings_;
      frame->settings.terms = terms_wanted_;
      frame->background = scene_.background;
    }
    try {
      frame->frame = session_.shade(scene, frame->settings, reusable_image(retired));
    } catch (const std::exception& error) {
      frame->error = error.what();
    }
    frame->finished = std::chrono::steady_clock::now();
    scene = Scene();
    // The copies a large scene's frame made (its tables, this thread's scene) are free now: back
    // to the system, or this thread's malloc arena keeps them (RoutedServer::answer does the same
    // for the request threads).
    if (large_scene) ::malloc_trim(0);
    rendered = frame->version;
    retired = std::exchange(shown, frame);
    std::lock_guard lock(mutex_);
    latest_ = std::move(frame);
    latest_taken_ = false;
    ++frames_;
    recent_finishes_.push_back(latest_->finished);
    const auto since = latest_->finished - kFpsWindow;
    std::erase_if(recent_finishes_, [&](auto t) { return t < since; });
    frame_ready_.notify_all();
  }
}

}  // namespace phongcl
