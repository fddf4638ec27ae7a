#include "cli/shadow_bench_report.h"

#include "report/markdown_table.h"

namespace phongcl::cli {

std::string shadow_rays_table(const ShadowRaysResult& result) {
  MarkdownTable table{{"tracer", "BVH build ms", "trace ms", "Mrays/s", "opencl / this", "decisions differing"},
                      {},
                      {ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                       ColumnAlign::right, ColumnAlign::right}};
  const double ours = result.tracers.empty() ? 0.0 : result.tracers.front().mrays_per_s;
  for (const ShadowTracerResult& tracer : result.tracers)
    table.rows.push_back({tracer.name, format_cell("%.1f", tracer.build_ms), format_cell("%.2f", tracer.trace_ms),
                          format_cell("%.1f", tracer.mrays_per_s), format_cell("%.2fx", ours / tracer.mrays_per_s),
                          format_cell("%.1e", tracer.disagreement)});
  return table.render();
}

}  // namespace phongcl::cli
