#pragma once
// A display processor made fast enough for every frame a server streams. OpenColorIO's CPU
// processor spends about 70 ns a pixel on Blender's Filmic view (a log shaper, a 65^3 3D LUT, a
// 1D LUT, applied op by op), 140 ms a 1080p frame on one core. The processor's optimised ops are
// regrouped here into stages that cost one table lookup per channel or one LUT interpolation:
//   - each run of per-channel ops (logs, 1D LUTs, ranges, exponents, diagonal matrices) becomes
//     one table per channel over the float's top 16 bits (sign, exponent and 7 mantissa bits),
//     interpolated linearly in the remaining 16 (a bucket spans 0.8% of its value);
//   - 3D LUTs are interpolated from their own grid as OpenColorIO does (tetrahedral or trilinear);
//   - matrices that mix channels stay 3x3 products.
// Each table is checked at every bucket's midpoint, and the whole pipeline on thousands of colours
// spread over 2^-16..2^16, against OpenColorIO's own processor; a pipeline with any other op, or one
// that strays by more than 0.5/255 (tables: 0.25/255 in display values, 5e-4 relative before), is
// applied with OpenColorIO's processor instead.
#include <cstddef>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

namespace phongcl {

struct PixelKernels;

class ViewPipeline {
 public:
  explicit ViewPipeline(OCIO_NAMESPACE::ConstProcessorRcPtr processor);

  // In place: n pixels' planes of finite values (clamp infinities to +-FLT_MAX) into display values,
  // with the given per-pixel loops (color/pixel_kernels.h). Const: threads may apply blocks at once.
  void apply(float* const planes[3], std::size_t n, const PixelKernels& kernels) const;
  bool compiled() const { return !stages_.empty(); }
  std::string description() const { return description_; }

  // One table per channel (color/display_math.h's table_lookup); channels with the same function
  // share one (a view's curve is usually the same for R, G and B: a third of the cache).
  struct Separable {
    std::shared_ptr<const std::vector<float>> table[3];  // 65536 + 1 entries
  };
  struct Lut3d {
    int size = 0;
    bool tetrahedral = true;
    std::vector<float> rgb;  // ((b * size + g) * size + r) * 3 + channel, and a float of padding
  };
  struct Matrix {
    float m[3][3];
    float offset[3];
  };
  using Stage = std::variant<Separable, Lut3d, Matrix>;

  // The one stage, when the whole view is one table per channel; else nullptr.
  const Separable* only_table() const {
    return stages_.size() == 1 ? std::get_if<Separable>(&stages_.front()) : nullptr;
  }

 private:
  OCIO_NAMESPACE::ConstCPUProcessorRcPtr fallback_;
  std::vector<Stage> stages_;  // empty: the fallback
  std::string description_;
};

}  // namespace phongcl
