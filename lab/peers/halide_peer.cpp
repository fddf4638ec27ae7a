#include "peers/halide_peer.h"

#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

#include "peers/packed_file.h"

namespace phongcl {

namespace {

// A private directory for the exchange files, removed with everything in it.
struct ExchangeDirectory {
  std::filesystem::path path;
  ExchangeDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "phongcl-halide-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::system_error(errno, std::generic_category(), "cannot create " + pattern);
    path = pattern;
  }
  ~ExchangeDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  ExchangeDirectory(const ExchangeDirectory&) = delete;
  ExchangeDirectory& operator=(const ExchangeDirectory&) = delete;
};

std::string shell_quoted(const std::filesystem::path& path) {
  std::string quoted = "'";
  for (char c : path.string()) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string contents_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::optional<std::filesystem::path> find_halide_peer(const std::filesystem::path& directory) {
  const std::filesystem::path candidate = directory / kHalidePeerExecutable;
  std::error_code error;
  if (std::filesystem::is_regular_file(candidate, error)) return candidate;
  return std::nullopt;
}

HalidePeerRun run_halide_peer(const std::filesystem::path& executable, const PackedFrame& frame, const PackedScene& scene,
                              int runs, double budget_ms, float* rgba) {
  const ExchangeDirectory exchange;
  const auto input = exchange.path / "input.packed", output = exchange.path / "rgba.f32", errors = exchange.path / "stderr.txt";
  write_packed_inputs(input, frame, scene);

  const std::string command = shell_quoted(executable) + " --input " + shell_quoted(input) + " --output " + shell_quoted(output) +
                              " --runs " + std::to_string(runs) + " --budget-ms " + std::to_string(budget_ms) + " 2>" +
                              shell_quoted(errors);
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::system_error(errno, std::generic_category(), "cannot start " + executable.string());
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = pclose(pipe);
  if (status != 0) {
    std::string message = contents_of(errors);
    while (!message.empty() && message.back() == '\n') message.pop_back();
    throw std::runtime_error(executable.filename().string() + " failed (status " + std::to_string(status) + "): " + message);
  }

  HalidePeerRun run;
  try {
    const nlohmann::json result = nlohmann::json::parse(out);
    run.schedule = result.at("schedule").get<std::string>();
    run.target = result.at("target").get<std::string>();
    run.compile_ms = result.at("compile_ms").get<double>();
    run.threads = result.at("threads").get<int>();
    run.times_ms = result.at("times_ms").get<std::vector<double>>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(executable.filename().string() + " printed no valid result (" + e.what() + "): " + out);
  }
  std::ifstream image(output, std::ios::binary);
  const auto bytes = static_cast<std::streamsize>(frame.pixels * 4 * sizeof(float));
  if (!image.read(reinterpret_cast<char*>(rgba), bytes)) throw std::runtime_error(executable.filename().string() + " wrote a short image");
  return run;
}

}  // namespace phongcl
