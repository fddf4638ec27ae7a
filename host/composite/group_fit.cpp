#include "composite/group_fit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace phongcl {

namespace {

bool lit(const float* d, const float* s) {
  return d[0] > 0.0f || d[1] > 0.0f || d[2] > 0.0f || s[0] > 0.0f || s[1] > 0.0f || s[2] > 0.0f;
}

}  // namespace

GroupFit fit_group(const Image& rendered, const GroupTerms& terms) {
  for (const Image* image : {&terms.diffuse, &terms.specular})
    if (image->width != rendered.width || image->height != rendered.height)
      throw std::invalid_argument("phongcl's terms of a group and its rendered pass differ in size");
  // Per channel, the normal equations of r ~ a d + b s: [dd ds; ds ss] [a b]' = [rd rs]'.
  double dd[3] = {}, ds[3] = {}, ss[3] = {}, rd[3] = {}, rs[3] = {}, rr = 0.0;
  GroupFit fit;
  for (std::size_t i = 0; i < rendered.pixel_count(); ++i) {
    const float *r = rendered.pixel(i), *d = terms.diffuse.pixel(i), *s = terms.specular.pixel(i);
    if (!lit(d, s)) continue;
    ++fit.pixels;
    for (int c = 0; c < 3; ++c) {
      dd[c] += double(d[c]) * d[c], ds[c] += double(d[c]) * s[c], ss[c] += double(s[c]) * s[c];
      rd[c] += double(r[c]) * d[c], rs[c] += double(r[c]) * s[c], rr += double(r[c]) * r[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double determinant = dd[c] * ss[c] - ds[c] * ds[c];
    if (determinant > 1e-9 * dd[c] * ss[c]) {
      fit.diffuse_gain[c] = (rd[c] * ss[c] - rs[c] * ds[c]) / determinant;
      fit.specular_gain[c] = (rs[c] * dd[c] - rd[c] * ds[c]) / determinant;
    } else if (const double sum = dd[c] + 2.0 * ds[c] + ss[c]; sum > 0.0) {
      fit.diffuse_gain[c] = fit.specular_gain[c] = std::max(0.0, (rd[c] + rs[c]) / sum);
    }
    // Light is not negative: where the best gains have one below 0, that term's gain is 0 and the
    // other's is fitted alone (the least-squares solution with both gains >= 0).
    if (fit.diffuse_gain[c] < 0.0) {
      fit.diffuse_gain[c] = 0.0;
      fit.specular_gain[c] = ss[c] > 0.0 ? std::max(0.0, rs[c] / ss[c]) : 0.0;
    } else if (fit.specular_gain[c] < 0.0) {
      fit.specular_gain[c] = 0.0;
      fit.diffuse_gain[c] = dd[c] > 0.0 ? std::max(0.0, rd[c] / dd[c]) : 0.0;
    }
  }
  double left = 0.0;
  for (std::size_t i = 0; i < rendered.pixel_count(); ++i) {
    const float *r = rendered.pixel(i), *d = terms.diffuse.pixel(i), *s = terms.specular.pixel(i);
    if (!lit(d, s)) continue;
    for (int c = 0; c < 3; ++c) left += std::pow(r[c] - fit.diffuse_gain[c] * d[c] - fit.specular_gain[c] * s[c], 2.0);
  }
  fit.residual = rr > 0.0 ? std::sqrt(left / rr) : 0.0;
  return fit;
}

}  // namespace phongcl
