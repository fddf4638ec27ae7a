#include "color/chromaticities.h"

namespace phongcl {

namespace {

std::array<double, 3> xyz_of(const std::array<float, 2>& xy) {  // Y = 1
  return {xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]};
}

double determinant(const Matrix3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

std::array<float, 2> xy_of(double x, double y, double z) {
  const double sum = x + y + z;
  return {static_cast<float>(x / sum), static_cast<float>(y / sum)};
}

}  // namespace

Matrix3 inverse(const Matrix3& m) {
  const double d = determinant(m);
  Matrix3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // cofactor of m[j][i], by the cyclic rule (signs come out of the index rotation)
      const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, e = (i + 2) % 3;
      r[i][j] = (m[a][c] * m[b][e] - m[a][e] * m[b][c]) / d;
    }
  return r;
}

Matrix3 rgb_to_xyz(const Chromaticities& c) {
  const std::array<double, 3> r = xyz_of(c.red), g = xyz_of(c.green), b = xyz_of(c.blue), w = xyz_of(c.white);
  const Matrix3 primaries{{{r[0], g[0], b[0]}, {r[1], g[1], b[1]}, {r[2], g[2], b[2]}}};
  const Matrix3 inv = inverse(primaries);
  Matrix3 m{};
  for (int j = 0; j < 3; ++j) {
    const double scale = inv[j][0] * w[0] + inv[j][1] * w[1] + inv[j][2] * w[2];  // each primary's share of white
    for (int i = 0; i < 3; ++i) m[i][j] = primaries[i][j] * scale;
  }
  return m;
}

Chromaticities chromaticities_of(const Matrix3& m) {
  Chromaticities c;
  c.red = xy_of(m[0][0], m[1][0], m[2][0]);
  c.green = xy_of(m[0][1], m[1][1], m[2][1]);
  c.blue = xy_of(m[0][2], m[1][2], m[2][2]);
  c.white = xy_of(m[0][0] + m[0][1] + m[0][2], m[1][0] + m[1][1] + m[1][2], m[2][0] + m[2][1] + m[2][2]);
  return c;
}

}  // namespace phongcl
