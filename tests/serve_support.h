#pragma once
// A real phongcl server (host/serve/) on an ephemeral loopback port, run on its own thread and
// stopped at the end, for the serve tests.
#include <httplib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "color/color_config.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "serve/relight_server.h"
#include "temp_dir.h"

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

// PUT `body` to `path`, which must answer 200.
inline void put_json(httplib::Client& client, const char* path, const nlohmann::json& body) {
  const auto result = client.Put(path, body.dump(), "application/json");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << path << ": " << result->body;
}

// The frame of the state as held now, as the EXR the server sends (empty, with a failure, if none).
inline Image served_exr(httplib::Client& client) {
  const auto result = client.Get("/api/image?format=exr");
  if (!result || result->status != 200) {
    ADD_FAILURE() << "no image: " << (result ? result->body : "no response");
    return {};
  }
  TempDir dir("served_image");
  std::ofstream(dir / "image.exr", std::ios::binary) << result->body;
  return read_exr(dir / "image.exr");
}

}  // namespace phongcl::testing
