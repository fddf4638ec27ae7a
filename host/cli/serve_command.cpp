// phongcl serve: interactive relighting in the browser (host/serve/).
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "cli/commands.h"
#include "cli/format.h"
#include "cli/inputs.h"
#include "cli/outputs.h"
#include "common/same_file.h"
#include "common/error.h"
#include "serve/relight_server.h"

namespace phongcl::cli {

namespace {

using Clock = std::chrono::steady_clock;

// How long a stop waits for the frame being shaded, from the signal: the connections close within
// HttpLimits::stop_time meanwhile, and the process ends within 2 s whatever the render does.
constexpr std::chrono::seconds kRenderGrace{1};

struct ServeArguments {
  SceneInputs inputs;
  std::string host = "127.0.0.1";
  int port = 8080;
  std::string save;
  std::string device;
  std::string precision = "precise";
  std::string over;  // a render to composite every frame over
};

std::string read_text(const std::string& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(file, "cannot open");
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// "shot.exr, view layer ViewLayer, light-group passes key, fill, rim".
std::string over_description(const RenderCompositor& over) {
  const RenderPasses& passes = over.passes();
  std::string groups;
  for (const auto& [group, pass] : passes.group_passes) groups += (groups.empty() ? "" : ", ") + group;
  return over.file().string() + (passes.layer.empty() ? "" : ", view layer " + passes.layer.substr(0, passes.layer.size() - 1)) +
         (groups.empty() ? ", no light-group passes" : ", light-group passes " + groups) +
         " (each frame composited over it: docs/compositing.md)";
}

bool is_loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

// SIGINT and SIGTERM are blocked in every thread (before any is started, PoCL's included) and
// taken here synchronously, so stopping is ordinary code rather than a signal handler.
sigset_t stop_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  return signals;
}

void run_serve(const ServeArguments& args) {
  const sigset_t signals = stop_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  if (args.inputs.camera_space())
    throw std::invalid_argument("serve: --space camera is not supported (lights are edited in the scene's world space)");
  // --save is checked now, not at the first POST /api/save: it must be writable and not an input.
  const auto refuse_save_over_inputs = [&](const Scene* scene) {
    std::vector<NamedFile> files = args.inputs.named_files(scene);
    if (!args.over.empty()) files.push_back({"--over", args.over});
    if (!args.save.empty()) files.push_back({"--save", args.save, true});
    refuse_shared_files(files);
  };
  refuse_save_over_inputs(nullptr);
  if (!args.save.empty()) check_destination(args.save);
  const Scene scene = args.inputs.load_scene();
  refuse_save_over_inputs(&scene);
  const LoadedGBuffer loaded = args.inputs.load_described_gbuffer(scene, /*with_beauty=*/true);
  const std::string scene_text = read_text(args.inputs.scene_file);
  RelightSession session(loaded.gbuffer, args.device,
                         args.over.empty() ? std::nullopt : std::optional<std::filesystem::path>(args.over));
  const std::string device = session.device_description();
  RenderSettings settings;
  settings.precision = parse_precision(args.precision);
  LiveRelighter live(session, scene_text, scene.source, settings, *args.inputs.color_config());
  RelightServer server(live, {.host = args.host, .port = args.port, .save_path = args.save, .device = device,
                              .limits = {}});  // the default limits

  const std::string host = args.host.find(':') != std::string::npos ? "[" + args.host + "]" : args.host;
  std::cout << "phongcl serve: " << scene.source.string() << " + " << loaded.gbuffer.source.string() << "\n"
            << "  layout     " << loaded.layout << "\n"
            << "  image      " << session.width() << " x " << session.height() << "\n"
            << "  device     " << device << "\n"
            << "  colour     " << args.inputs.color_config()->description() << ", working space "
            << args.inputs.color_config()->working_space() << "\n"
            << (loaded.beauty.empty() ? "" : "  beauty     " + loaded.beauty + " (GET /api/beauty, the page's before/after split)\n")
            << (session.over() ? "  over       " + over_description(*session.over()) + "\n" : "")
            << (args.save.empty() ? "" : "  save       " + args.save + " (POST /api/save, the page's Save button)\n");
  if (!is_loopback(args.host))
    std::cout << "  warning    listening on " << args.host
              << ": anyone who can reach this address can read and change the scene and read the G-buffer\n";
  const int port = server.bind();

  std::atomic<bool> done = false;
  std::optional<Clock::time_point> signalled;  // written by the waiter, read after joining it
  std::thread signal_waiter([&] {
    const timespec poll{0, 200'000'000};
    while (!done) {
      const int signal = sigtimedwait(&signals, nullptr, &poll);
      if (signal == SIGINT || signal == SIGTERM) {
        signalled = Clock::now();
        std::cout << "phongcl serve: " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << ", stopping" << std::endl;
        server.stop();
        return;
      }
    }
  });

  std::cout << "  url        http://" << host << ":" << port << "/" << std::endl;
  server.run();
  done = true;
  signal_waiter.join();
  // Every connection is closed. A frame still being shaded past the grace time (a mesh of millions of
  // triangles being read, a reader that hangs) is abandoned: the destructors of what the render
  // thread uses (the LiveRelighter, the session, the device) would wait for it, or free memory it is
  // using. Nothing else is left to finish (saves are written whole, atomically before they answer).
  if (!live.render_thread_ended_by(signalled.value_or(Clock::now()) + kRenderGrace)) {
    std::cout << "phongcl serve: stopped (the frame being shaded is abandoned)" << std::endl;
    std::fflush(nullptr);
    std::_Exit(0);  // as a normal stop
  }
  std::cout << "phongcl serve: stopped" << std::endl;
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto args = std::make_shared<ServeArguments>();
  CLI::App* command = app.add_subcommand("serve", "Relight interactively in the browser (HTTP server and page)");
  args->inputs.add_options(*command);
  command->add_option("--port", args->port, "TCP port (default 8080; 0: any free port)")->check(CLI::Range(0, 65535));
  command->add_option("--host", args->host, "Address to listen on (default 127.0.0.1, this machine only)");
  command->add_option("--save", args->save, "Scene file the page's Save button writes (atomically)");
  command->add_option("--device", args->device, "OpenCL device: index or name (default: first CPU device)");
  command->add_option("--precision", args->precision, "Starting precision: double, precise (default), fast or half-storage")
      ->check(CLI::IsMember({"double", "precise", "fast", "half-storage"}));
  command->add_option("--over", args->over,
                      "A render of the G-buffer with light-group passes (Blender's Combined_<group>): every frame is "
                      "that render with the groups the page changed scaled or re-shaded by phongcl (docs/compositing.md)");
  command->callback([args] { run_serve(*args); });
}

}  // namespace phongcl::cli
