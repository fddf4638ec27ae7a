#pragma once
// The many-lights benchmark's results and their outputs: the Markdown table, the JSON other tools
// read ({"machine": {...}, "results": [...]}) and the report directory (report.md, results.json,
// frame_ms_vs_lights.svg).
#include <optional>
#include <string>
#include <vector>

#include "cli/throughput_report.h"

namespace phongcl::cli {

struct ManyLightsResult {
  std::string impl;  // "opencl-tiled" | "opencl-unculled" | "cpp-tiled" | "cpp-tiled-best"
  std::string schedule;  // cpp-tiled's (TiledPeerSchedule), e.g. "tiles 16, coarse 8, 4 tiles/task"
  int lights = 0;
  RunStats time;                      // ms per frame: opencl kernel time (culling included), cpp wall clock
  std::optional<double> culling_ms;   // median of the culling part; tiled only
  double mean_lights_per_pixel = 0.0;  // the pairs shaded: kept by culling, or every light
  double mean_lights_reaching = 0.0;   // lights with d < range (and inside a spot's cone) per shaded pixel
  double mean_lights_reaching_tile = 0.0;  // lights that reach a shaded pixel of the pixel's tile
  double mean_lights_per_tile = 0.0;   // tiled only
  double mean_holding_per_tile = 0.0;  // tiled only: of them, the lights whose bounds hold all of the tile
  double effective_mpix_lights_per_s = 0.0;
  std::optional<double> max_rel_err;  // against the double reference on a sample of rows
  bool single_run = false;            // one timed run: a run took over 10 s
};

struct ManyLightsMachine {
  std::string cpu, device, loadavg;
  int cores = 0;
  int width = 0, height = 0, tile_size = 16, list_rows = 8;  // tiles, and the rows each light list serves
  std::string inputs;
};

std::string many_lights_table(const std::vector<ManyLightsResult>& results);
std::string many_lights_json(const ManyLightsMachine& machine, const std::vector<ManyLightsResult>& results);
void write_many_lights_report(const std::string& directory, const ManyLightsMachine& machine,
                              const std::vector<ManyLightsResult>& results);

}  // namespace phongcl::cli
