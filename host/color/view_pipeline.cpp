#include "color/view_pipeline.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <sstream>

#include "color/display_math.h"
#include "color/pixel_kernels.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

namespace {

constexpr std::uint32_t kBuckets = 1u << (32 - kTableShift);
constexpr double kTableTolerance = 0.25 / 255;     // a table that ends in display values
constexpr double kRelativeTolerance = 5e-4;         // a table that feeds another stage
constexpr double kPipelineTolerance = 0.5 / 255;    // the whole pipeline, in display values

bool is_nan_bucket(std::uint32_t bucket) { return (bucket & 0x7fffu) > 0x7f80u; }

float bucket_start(std::uint32_t bucket) { return std::bit_cast<float>(bucket << kTableShift); }

double unit(double v) { return v > 0.0 ? std::min(v, 1.0) : 0.0; }  // NaN -> 0

void apply_stage(const PixelKernels& kernels, const ViewPipeline::Stage& stage, float* const planes[3], std::size_t n) {
  if (const auto* s = std::get_if<ViewPipeline::Separable>(&stage)) {
    const float* tables[3] = {s->table[0]->data(), s->table[1]->data(), s->table[2]->data()};
    return kernels.separable(tables, planes, n);
  }
  if (const auto* l = std::get_if<ViewPipeline::Lut3d>(&stage)) return kernels.lut3d(l->rgb.data(), l->size, l->tetrahedral, planes, n);
  const auto& m = std::get<ViewPipeline::Matrix>(stage);
  kernels.matrix(m.m, m.offset, planes, n);
}

void apply_cpu(const OCIO::ConstCPUProcessorRcPtr& cpu, float* const planes[3], std::size_t n) {
  OCIO::PlanarImageDesc image(planes[0], planes[1], planes[2], nullptr, static_cast<long>(n), 1);
  cpu->apply(image);
}

// Interleaved RGB as planes, for the checks.
struct Planes {
  std::vector<float> plane[3];
  explicit Planes(const std::vector<float>& rgb) {
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = c; i < rgb.size(); i += 3) plane[c].push_back(rgb[i]);
  }
  std::size_t size() const { return plane[0].size(); }
  float* pointers[3] = {};
  float* const* data() {
    for (int c = 0; c < 3; ++c) pointers[c] = plane[c].data();
    return pointers;
  }
};

// The ops carry their data, so any config makes their processor; this one caches none, because
// OpenColorIO 2.1 keys its cache by a transform's text, which for LUTs leaves out their values.
OCIO::ConstConfigRcPtr uncached_config() {
  OCIO::ConfigRcPtr config = OCIO::Config::CreateRaw()->createEditableCopy();
  config->setProcessorCacheFlags(OCIO::PROCESSOR_CACHE_OFF);
  return config;
}

OCIO::ConstCPUProcessorRcPtr cpu_of(const OCIO::ConstTransformRcPtr& transform) {
  static const OCIO::ConstConfigRcPtr config = uncached_config();
  return config->getProcessor(transform)->getDefaultCPUProcessor();
}

std::string op_name(const OCIO::ConstTransformRcPtr& transform) {
  std::ostringstream text;
  text << *transform;
  const std::string full = text.str();
  return full.substr(1, full.find_first_of(" >") - 1);  // "<LogTransform direction=..." -> LogTransform
}

// A run of per-channel ops as tables, or an empty optional with the reason when a table strays
// from the ops (checked at every bucket's midpoint).
std::optional<ViewPipeline::Separable> tabulate(const OCIO::GroupTransformRcPtr& run, bool ends_in_display,
                                                std::string& failure) {
  const OCIO::ConstCPUProcessorRcPtr cpu = cpu_of(run);
  std::vector<float> values(3 * kBuckets);
  constexpr float kMax = std::numeric_limits<float>::max();
  for (std::uint32_t b = 0; b < kBuckets; ++b) {
    // Inputs are finite (apply()'s contract): the slot of +-Inf only ends the last finite bucket, at
    // +-FLT_MAX (the function's limit there, where Inf's own value may be too far to interpolate
    // to), and NaN buckets are never read.
    const bool beyond = is_nan_bucket(b) || (b & 0x7fffu) == 0x7f80u;
    const float x = beyond ? std::copysign(kMax, bucket_start(b)) : bucket_start(b);
    values[3 * b] = values[3 * b + 1] = values[3 * b + 2] = x;
  }
  Planes outputs(values);
  apply_cpu(cpu, outputs.data(), kBuckets);
  ViewPipeline::Separable stage;
  for (int c = 0; c < 3; ++c) {
    std::vector<float> table(kBuckets + 1);
    for (std::uint32_t b = 0; b < kBuckets; ++b) {
      const float v = outputs.plane[c][b];
      table[b] = std::isnan(v) ? 0.0f : std::clamp(v, -kMax, kMax);  // finite: interpolation multiplies by 0
    }
    table[kBuckets] = table[kBuckets - 1];
    const auto same = std::find_if(stage.table, stage.table + c, [&](const auto& other) { return *other == table; });
    stage.table[c] = same != stage.table + c ? *same : std::make_shared<const std::vector<float>>(std::move(table));
  }
  std::vector<float> middles;
  for (std::uint32_t b = 0; b < kBuckets; ++b)
    if ((b & 0x7fffu) < 0x7f80u) {  // finite buckets
      const float x = std::bit_cast<float>((b << kTableShift) | (1u << 15));
      middles.insert(middles.end(), {x, x, x});
    }
  Planes exact(middles);
  apply_cpu(cpu, exact.data(), exact.size());
  for (std::size_t i = 0; i < middles.size(); ++i) {
    const double table = table_lookup(stage.table[i % 3]->data(), middles[i]), ops = exact.plane[i % 3][i / 3];
    if (std::isnan(ops)) continue;
    const double error = ends_in_display ? std::abs(unit(table) - unit(ops)) : std::abs(table - ops) / std::max(1.0, std::abs(ops));
    if (error > (ends_in_display ? kTableTolerance : kRelativeTolerance)) {
      std::ostringstream text;
      text << "a per-channel table strays by " << error << " at " << middles[i];
      failure = text.str();
      return std::nullopt;
    }
  }
  return stage;
}

std::optional<ViewPipeline::Stage> lut3d_stage(const OCIO::ConstLut3DTransformRcPtr& lut) {
  if (lut->getDirection() != OCIO::TRANSFORM_DIR_FORWARD) return std::nullopt;
  const OCIO::Interpolation interpolation = lut->getInterpolation();
  ViewPipeline::Lut3d stage;
  if (interpolation == OCIO::INTERP_BEST || interpolation == OCIO::INTERP_TETRAHEDRAL) stage.tetrahedral = true;
  else if (interpolation == OCIO::INTERP_DEFAULT || interpolation == OCIO::INTERP_LINEAR) stage.tetrahedral = false;
  else return std::nullopt;
  stage.size = static_cast<int>(lut->getGridSize());
  if (stage.size < 2) return std::nullopt;
  stage.rgb.resize(3 * static_cast<std::size_t>(stage.size) * stage.size * stage.size + 1);  // + padding (pixel_kernels.h)
  std::size_t i = 0;
  for (int b = 0; b < stage.size; ++b)
    for (int g = 0; g < stage.size; ++g)
      for (int r = 0; r < stage.size; ++r, i += 3) lut->getValue(r, g, b, stage.rgb[i], stage.rgb[i + 1], stage.rgb[i + 2]);
  return stage;
}

std::optional<ViewPipeline::Stage> matrix_stage(const OCIO::ConstMatrixTransformRcPtr& transform) {
  if (transform->getDirection() != OCIO::TRANSFORM_DIR_FORWARD) return std::nullopt;
  double m44[16], offset[4];
  transform->getMatrix(m44);
  transform->getOffset(offset);
  ViewPipeline::Matrix stage;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) stage.m[r][c] = static_cast<float>(m44[4 * r + c]);
    stage.offset[r] = static_cast<float>(offset[r]);
  }
  return stage;
}

// The processor's ops as stages, or an empty list and the reason.
std::vector<ViewPipeline::Stage> compile(const OCIO::ConstProcessorRcPtr& processor, std::string& failure) {
  const OCIO::GroupTransformRcPtr ops = processor->getOptimizedProcessor(OCIO::OPTIMIZATION_DEFAULT)->createGroupTransform();
  std::vector<ViewPipeline::Stage> stages;
  OCIO::GroupTransformRcPtr run = OCIO::GroupTransform::Create();
  const auto end_run = [&](bool last) {
    if (run->getNumTransforms() == 0 && !(last && stages.empty())) return true;
    const auto table = tabulate(run, last, failure);
    if (!table) return false;
    stages.emplace_back(*table);
    run = OCIO::GroupTransform::Create();
    return true;
  };
  for (int i = 0; i < ops->getNumTransforms(); ++i) {
    const OCIO::ConstTransformRcPtr op = ops->getTransform(i);
    if (!cpu_of(op)->hasChannelCrosstalk()) {
      run->appendTransform(op->createEditableCopy());
      continue;
    }
    std::optional<ViewPipeline::Stage> stage;
    if (const auto lut = OCIO::DynamicPtrCast<const OCIO::Lut3DTransform>(op)) stage = lut3d_stage(lut);
    else if (const auto matrix = OCIO::DynamicPtrCast<const OCIO::MatrixTransform>(op)) stage = matrix_stage(matrix);
    if (!stage) {
      failure = op_name(op) + " mixes channels";
      return {};
    }
    if (!end_run(false)) return {};
    stages.push_back(std::move(*stage));
  }
  if (!end_run(true)) return {};
  return stages;
}

// Colours spread over 2^-16..2^16 per channel (saturated and near-grey), zeros, ones, negatives.
std::vector<float> probe_colors() {
  std::mt19937 random(6502);
  std::uniform_real_distribution<double> stops(-16.0, 16.0), near(-0.3, 0.3);
  std::vector<float> colors;
  for (int i = 0; i < 4096; ++i) {
    const double base = stops(random);
    for (int c = 0; c < 3; ++c) colors.push_back(static_cast<float>(std::exp2(i % 2 ? stops(random) : base + near(random))));
  }
  colors.insert(colors.end(), {0, 0, 0, 1, 1, 1, 0.18f, 0.18f, 0.18f, 1e6f, 1e6f, 1e6f, -0.5f, 0.2f, 0.1f, 0, 0, 1e4f});
  return colors;
}

}  // namespace

ViewPipeline::ViewPipeline(OCIO::ConstProcessorRcPtr processor) : fallback_(processor->getDefaultCPUProcessor()) {
  std::string failure;
  std::vector<Stage> stages = compile(processor, failure);
  if (!stages.empty()) {
    Planes compiled(probe_colors()), exact(probe_colors());
    for (const Stage& stage : stages) apply_stage(scalar_pixel_kernels(), stage, compiled.data(), compiled.size());
    apply_cpu(fallback_, exact.data(), exact.size());
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < exact.size(); ++i)
        worst = std::max(worst, std::abs(unit(compiled.plane[c][i]) - unit(exact.plane[c][i])));
    if (worst > kPipelineTolerance) {
      std::ostringstream text;
      text << "the compiled stages stray by " << worst * 255 << "/255";
      failure = text.str();
      stages.clear();
    }
  }
  stages_ = std::move(stages);
  if (stages_.empty()) {
    description_ = "OpenColorIO's CPU processor (" + failure + ")";
    return;
  }
  std::ostringstream text;
  text << "compiled:";
  const char* separator = " ";
  for (const Stage& stage : stages_) {
    text << separator;
    separator = ", ";
    if (std::holds_alternative<Separable>(stage)) text << "per-channel table";
    if (const auto* lut = std::get_if<Lut3d>(&stage))
      text << lut->size << "^3 LUT (" << (lut->tetrahedral ? "tetrahedral" : "trilinear") << ")";
    if (std::holds_alternative<Matrix>(stage)) text << "3x3 matrix";
  }
  description_ = text.str();
}

void ViewPipeline::apply(float* const planes[3], std::size_t n, const PixelKernels& kernels) const {
  if (stages_.empty()) return apply_cpu(fallback_, planes, n);
  for (const Stage& stage : stages_) apply_stage(kernels, stage, planes, n);
}

}  // namespace phongcl
