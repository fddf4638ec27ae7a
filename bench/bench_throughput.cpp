// The C++ peers and the OpenCL kernel at 1920x1080 with 16 generated lights (8 point, 8
// directional), on a G-buffer ray-cast from scenes/large at start-up.
//   peers: wall clock of the shading loop; input packed once before timing.
//   opencl/<variant>: manual time = kernel time from profiling events (the build is cached by the
//   untimed warm-up); counter end_to_end_ms = pack + upload + kernel + download.
// Counters: Mpixels/s and Mpixel-lights/s from the time Google Benchmark reports.
#include <benchmark/benchmark.h>

#include <memory>

#include "cl/compute_context.h"
#include "peers/light_sweep.h"
#include "peers/peers.h"
#include "raycast/raycast.h"
#include "shading/phong_shader.h"

namespace phongcl {
namespace {

constexpr int kLights = 16;

struct Frame {
  Scene scene;
  GBuffer gbuffer;
};

const Frame& frame() {
  static const Frame frame = [] {
    Scene scene = load_scene(PHONGCL_SOURCE_DIR "/scenes/large/scene.json");
    scene.camera.width = 1920;
    scene.camera.height = 1080;
    GBuffer gbuffer = generate_gbuffer(scene);
    return Frame{with_generated_lights(scene, kLights), std::move(gbuffer)};
  }();
  return frame;
}

void set_rates(benchmark::State& state) {
  const double pixels = static_cast<double>(frame().gbuffer.pixel_count());
  state.counters["Mpix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["Mpix-lights/s"] = benchmark::Counter(pixels * kLights / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

template <void (*Shade)(const PackedFrame&, const PackedScene&, float*)>
void BM_Peer(benchmark::State& state) {
  const PackedFrame packed = pack_frame(frame().gbuffer, frame().scene);
  const PackedScene scene = pack_scene(frame().scene);
  Image output = image_like(frame().gbuffer);
  for (auto _ : state) {
    Shade(packed, scene, output.rgba.data());
    benchmark::DoNotOptimize(output.rgba.data());
  }
  set_rates(state);
}
// Real time: the SIMD peer runs on every core, and CPU time would count only the calling thread.
BENCHMARK(BM_Peer<shade_scalar>)->Name("cpp-scalar")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_Peer<shade_simd>)->Name("cpp-simd")->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

PhongShader* shader() {
  static std::unique_ptr<ProgramCache> cache;
  static std::unique_ptr<PhongShader> instance;
  if (!instance && !list_devices().empty()) {
    cache = std::make_unique<ProgramCache>(ProgramCache::default_directory());
    instance = std::make_unique<PhongShader>(make_compute_context(pick_device("")), *cache);
  }
  return instance.get();
}

void BM_OpenCL(benchmark::State& state, Precision precision) {
  PhongShader* phong = shader();
  if (!phong) return state.SkipWithError("no OpenCL device on this machine");
  if (precision == Precision::double_precision && !phong->compute().device.info.has_fp64) {
    return state.SkipWithError("device has no fp64");
  }
  const ShadeOptions options{precision, true};
  phong->shade(frame().scene, frame().gbuffer, options);  // warm-up: build and cache the kernel
  double end_to_end_ms = 0.0;
  for (auto _ : state) {
    const ShadeResult result = phong->shade(frame().scene, frame().gbuffer, options);
    state.SetIterationTime(result.timings.kernel_ms / 1e3);
    end_to_end_ms += result.timings.total_ms;
  }
  set_rates(state);
  state.counters["end_to_end_ms"] = benchmark::Counter(end_to_end_ms, benchmark::Counter::kAvgIterations);
}

void register_opencl() {
  for (Precision precision : all_precisions()) {
    benchmark::RegisterBenchmark(("opencl/" + to_string(precision)).c_str(), BM_OpenCL, precision)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2.0);
  }
}

}  // namespace
}  // namespace phongcl

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  phongcl::register_opencl();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
