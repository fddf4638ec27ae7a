#pragma once
// A stability run as text: a fixed-width table for the terminal, Markdown and JSON for the report.
#include <string>

#include "stability/accuracy_bars.h"
#include "stability/run_catalogue.h"

namespace phongcl {

std::string stability_table(const StabilityRun& run);
std::string stability_markdown(const StabilityRun& run, const std::vector<BarFigure>& bars);
std::string stability_json(const StabilityRun& run, const std::vector<BarFigure>& bars);

}  // namespace phongcl
