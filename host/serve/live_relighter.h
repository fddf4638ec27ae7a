#pragma once
// The state the server holds and the thread that shades it. Edits replace the scene whole and
// only when valid; the render thread always shades the newest state, so edits that arrive while a
// frame is being shaded coalesce into the next one. It shades ahead by one frame at most: a newer
// state waits until the last frame was taken or a request waits for one, so that on a busy machine
// no core goes to frames nobody shows. Every request thread may call every method.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include <glm/glm.hpp>

#include "color/color_config.h"
#include "serve/relight_session.h"

namespace phongcl {

// A shaded frame and the state it shows. version counts every change of state (scene or
// settings); scene_version only scene changes, so a page can tell that another one edited it.
struct RenderedFrame {
  std::uint64_t version = 0, scene_version = 0;
  RenderSettings settings;
  glm::dvec3 background{0.0};  // the scene's (working space), under the image in 8-bit frames
  Frame frame;
  std::string error;  // non-empty: shading this state failed (the image is empty)
  std::chrono::steady_clock::time_point finished;
};

struct SceneSnapshot {
  std::uint64_t scene_version = 0;
  std::string json;  // the document as held, pretty-printed
  std::vector<std::string> light_groups;  // its lights' groups (light_groups())
  std::vector<std::filesystem::path> meshes;  // the mesh files its objects name (mesh_files())
};

struct RenderCounters {
  std::uint64_t frames = 0;     // frames shaded since start
  double frames_per_second = 0.0;  // frames finished in the last two seconds, per second
};

class LiveRelighter {
 public:
  // `scene_text` is the scene file's text and `scene_source` its path (for messages and to resolve
  // its "gbuffer" entry); its colours are converted to `color`'s working space. Throws InputError
  // when it is invalid. Starts the render thread.
  LiveRelighter(RelightSession& session, std::string_view scene_text, std::filesystem::path scene_source,
                RenderSettings settings, ColorConfig color);
  ~LiveRelighter();
  LiveRelighter(const LiveRelighter&) = delete;
  LiveRelighter& operator=(const LiveRelighter&) = delete;

  SceneSnapshot scene() const;
  // Parses and validates the whole scene (the CLI's checks, mesh files that open, then the G-buffer's
  // material indices); throws InputError with the one-line message and keeps the held scene otherwise.
  // The next frame shows every change, the objects' (shadow geometry, meshes read again) included.
  std::uint64_t replace_scene(std::string_view text);
  RenderSettings settings() const;
  void replace_settings(const RenderSettings& settings);

  // The first frame newer than `after_version` (showing terms if `need_terms`), waiting up to
  // `timeout`; nullptr on timeout or once stopping.
  std::shared_ptr<const RenderedFrame> wait_for_frame(std::uint64_t after_version, bool need_terms,
                                                      std::chrono::milliseconds timeout);
  // The frame showing the state as it is now (waiting for it to be shaded), or nullptr on timeout.
  std::shared_ptr<const RenderedFrame> current_frame(bool need_terms, std::chrono::milliseconds timeout);
  // The newest shaded frame (nullptr before the first), without waiting; reading it is not showing
  // it, so it does not let the render thread shade ahead.
  std::shared_ptr<const RenderedFrame> latest_frame() const;
  RenderCounters counters() const;
  RelightSession& session() { return session_; }
  const ColorConfig& color_config() const { return color_; }

  // Wakes every waiter and ends the render thread; idempotent.
  void stop();
  // After stop(): whether the render thread has ended by `deadline`. A frame in flight can outlast
  // any deadline (a mesh of millions of triangles being read, a reader that hangs), and this
  // object's destructor waits for it: a process that must end on time exits without running it.
  bool render_thread_ended_by(std::chrono::steady_clock::time_point deadline);

 private:
  void render_loop();
  Scene parsed_scene(std::string_view text) const;
  std::shared_ptr<const RenderedFrame> wait_locked(std::unique_lock<std::mutex>& lock, std::uint64_t min_version,
                                                   bool need_terms, std::chrono::milliseconds timeout);

  RelightSession& session_;
  const std::filesystem::path scene_source_;
  const ColorConfig color_;
  mutable std::mutex mutex_;
  std::condition_variable state_changed_, frame_ready_, render_ended_;
  // Guarded by mutex_:
  Scene scene_;
  std::string scene_json_;
  std::uint64_t version_ = 1, scene_version_ = 1;
  RenderSettings settings_;
  bool terms_wanted_ = false;  // sticky once a page asks for a term: the terms cost little more
  bool stopping_ = false;
  bool render_thread_done_ = false;
  std::shared_ptr<const RenderedFrame> latest_;
  bool latest_taken_ = true;  // a request has had latest_ (or there is none yet)
  int waiting_ = 0;           // requests waiting for a frame newer than latest_
  std::uint64_t frames_ = 0;
  std::vector<std::chrono::steady_clock::time_point> recent_finishes_;
  std::thread render_thread_;  // last: starts after everything above exists
};

}  // namespace phongcl
