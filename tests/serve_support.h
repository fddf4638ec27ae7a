#pragma once
// A real phongcl server (host/serve/) on an ephemeral loopback port, run on its own thread and
// stopped at the end, for the serve tests.
#include <httplib.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "cli_runner.h"
#include "color/color_config.h"
#include "gbuffer/gbuffer.h"
#include "serve/relight_server.h"

namespace phongcl::testing {

inline const std::filesystem::path kServeSceneFile = PHONGCL_SOURCE_DIR "/scenes/default/scene.json";

class RunningServer {
 public:
  explicit RunningServer(const std::filesystem::path& save_path = {}, const HttpLimits& limits = {})
      : RunningServer(read_gbuffer(PHONGCL_SOURCE_DIR "/scenes/default/gbuffer.exr"), kServeSceneFile, save_path, limits) {}
  // `over`: a render every frame is composited over (serve --over).
  RunningServer(GBuffer gbuffer, const std::filesystem::path& scene_file, const std::filesystem::path& save_path = {},
                const HttpLimits& limits = {}, std::optional<std::filesystem::path> over = std::nullopt)
      : session_(std::move(gbuffer), "", std::move(over)),
        live_(session_, read_text(scene_file), scene_file, RenderSettings{}, ColorConfig::builtin()),
        server_(live_, {"127.0.0.1", 0, save_path, "test device", limits}) {
    port_ = server_.bind();
    thread_ = std::thread([this] { server_.run(); });
  }
  ~RunningServer() {
    server_.stop();
    thread_.join();
  }
  httplib::Client client() const {
    httplib::Client client("127.0.0.1", port_);
    client.set_read_timeout(std::chrono::seconds(120));
    return client;
  }
  int port() const { return port_; }
  RelightSession& session() { return session_; }
  RelightServer& server() { return server_; }

 private:
  RelightSession session_;
  LiveRelighter live_;
  RelightServer server_;
  int port_ = 0;
  std::thread thread_;
};

}  // namespace phongcl::testing
