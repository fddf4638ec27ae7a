#include "reference/reference_area.h"

#include "reference/reference.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace phongcl {

using std::numbers::pi;

namespace {

struct GaussRule {
  std::vector<double> nodes, weights;  // on [0, 1]
};

// Legendre roots by Newton's method from Chebyshev guesses, mapped to [0, 1].
const GaussRule& gauss_rule(int order) {
  static thread_local std::map<int, GaussRule> rules;
  auto found = rules.find(order);
  if (found != rules.end()) return found->second;
  GaussRule rule;
  for (int i = 0; i < order; ++i) {
    double x = std::cos(pi * (i + 0.75) / (order + 0.5)), derivative = 0.0;
    for (int step = 0; step < 100; ++step) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= order; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = order * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.nodes.push_back((1.0 - x) / 2.0);
    rule.weights.push_back(1.0 / ((1.0 - x * x) * derivative * derivative));  // 2 / (...) halved for [0, 1]
  }
  return rules.emplace(order, std::move(rule)).first->second;
}

// Integral of f over [a, b]; graded (x = a + (b - a) y^3) where f may peak at a: a peak of width w
// at a becomes one of width (w / (b - a))^(1/3) in y, which the rule resolves down to w = 1e-6 (b - a).
template <typename F>
glm::dvec3 integrate(double a, double b, bool graded, int order, F&& f) {
  if (!(b > a)) return glm::dvec3(0.0);
  const GaussRule& rule = gauss_rule(order);
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    const double y = rule.nodes[i];
    if (graded) sum += rule.weights[i] * 3.0 * y * y * f(a + (b - a) * y * y * y);
    else sum += rule.weights[i] * f(a + (b - a) * y);
  }
  return sum * (b - a);
}

// Integral over [a, b] cut at the given points (those inside), each piece graded towards `focus`
// when it ends there.
template <typename F>
glm::dvec3 integrate_pieces(double a, double b, std::vector<double> cuts, double focus, int order, F&& f) {
  cuts.push_back(a);
  cuts.push_back(b);
  std::sort(cuts.begin(), cuts.end());
  glm::dvec3 sum(0.0);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double lo = std::clamp(cuts[k], a, b), hi = std::clamp(cuts[k + 1], a, b);
    if (!(hi > lo)) continue;
    if (hi == focus) sum += integrate(0.0, hi - lo, true, order, [&](double d) { return f(hi - d); });
    else sum += integrate(lo, hi, lo == focus, order, f);
  }
  return sum;
}

// A half-plane of the emitter's plane, base + gu s + gv t >= 0 in its (u, v) coordinates about the
// centre: the horizon n.x >= 0, and for q > 0 the lobe's side r.x >= 0, where the integrands have
// kinks; the rules integrate only between them.
struct HalfPlane {
  double base, gu, gv;
};

// The interval of t in [lo, hi] where base + slope * t >= 0, for each (base, slope).
std::pair<double, double> upper_side(const std::vector<std::pair<double, double>>& lines, double lo, double hi) {
  for (const auto& [base, slope] : lines) {
    if (slope == 0.0) {
      if (base < 0.0) hi = lo;
      continue;
    }
    const double root = -base / slope;
    if (slope > 0.0) lo = std::max(lo, root);
    else hi = std::min(hi, root);
  }
  return {lo, std::max(lo, hi)};
}

// Where two half-planes' edges meet, in (s, t); false if parallel.
bool corner(const HalfPlane& a, const HalfPlane& b, double& s, double& t) {
  const double det = a.gu * b.gv - a.gv * b.gu;
  if (det == 0.0) return false;
  s = (-a.base * b.gv + b.base * a.gv) / det;
  t = (-a.gu * b.base + b.gu * a.base) / det;
  return true;
}

// E and the integral of a coloured lobe (reference_area.h), each over its own pieces.
struct EmitterIntegrals {
  double irradiance = 0.0;
  glm::dvec3 lobe{0.0};
};

EmitterIntegrals integrate_emitter(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                                   const glm::dvec3& eye, const ColouredLobe& lobe, double sharpness, bool reflection_kink,
                                   int order);

}  // namespace

double area_range_window(const AreaLight& light, const glm::dvec3& position) {
  if (!light.has_range()) return 1.0;
  const double t = std::clamp(1.0 - std::pow(glm::length(light.position - position) / light.range, 4.0), 0.0, 1.0);
  return t * t;
}

AreaIntegrals reference_area_integrals(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                                       const glm::dvec3& eye, SpecularModel model, double shininess, int order) {
  // Phong's lobes have a kink where r.w = 0; Blinn's are smooth above the horizon of a pixel that
  // faces the eye (n.h > 0 there).
  const bool reflection = model == SpecularModel::phong || model == SpecularModel::phong_normalized;
  const EmitterIntegrals integrals = integrate_emitter(
      light, position, n, eye, [&](const glm::dvec3& w) { return glm::dvec3(reference_specular_lobe(model, n, eye, w, shininess)); },
      shininess, shininess > 0.0 && reflection, order);
  AreaIntegrals result;
  result.irradiance = integrals.irradiance;
  result.highlight = integrals.lobe.x;
  return result;
}

glm::dvec3 reference_area_lobe(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                               const glm::dvec3& eye, const ColouredLobe& lobe, double sharpness, bool reflection_kink,
                               int order) {
  return integrate_emitter(light, position, n, eye, lobe, sharpness, reflection_kink, order).lobe;
}

namespace {

EmitterIntegrals integrate_emitter(const AreaLight& light, const glm::dvec3& position, const glm::dvec3& n,
                                   const glm::dvec3& eye, const ColouredLobe& lobe, double sharpness, bool reflection_kink,
                                   int order) {
  const glm::dvec3 normal = glm::normalize(light.direction);
  const glm::dvec3 c = light.position - position;
  const double h = -glm::dot(c, normal);  // height above the emitting side
  EmitterIntegrals result;
  if (!(h > 0.0)) return result;
  const glm::dvec3 v = light.shape == AreaShape::rect
                           ? glm::normalize(light.up - glm::dot(light.up, normal) * normal)
                           : glm::normalize(glm::cross(std::abs(normal.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), normal));
  const glm::dvec3 u = glm::cross(v, normal);
  // The integrands over the emitter's area: dw = h dA / |x|^3.
  auto value = [&](const glm::dvec3& x, bool highlight) {
    const double length = glm::length(x);
    const glm::dvec3 w = x / length;
    const double solid = h / (length * length * length);
    if (!highlight) return glm::dvec3(solid * std::max(0.0, glm::dot(n, w)));
    return glm::dot(n, w) > 0.0 ? solid * lobe(w) : glm::dvec3(0.0);
  };
  std::vector<HalfPlane> sides = {{glm::dot(n, c), glm::dot(n, u), glm::dot(n, v)}};
  const glm::dvec3 r = 2.0 * glm::dot(n, eye) * n - eye;
  if (reflection_kink) sides.push_back({glm::dot(r, c), glm::dot(r, u), glm::dot(r, v)});
  // The lobe peaks where r meets the emitter's plane (Blinn's too: n.h = 1 where w = r), with a
  // width of about its distance / sqrt(q + 1): cuts there, growing geometrically from a quarter of it.
  std::vector<double> peak_steps;
  glm::dvec3 peak(0.0);
  if (sharpness > 0.0 && glm::dot(r, normal) < 0.0) {
    const double distance = -h / glm::dot(r, normal);
    peak = distance * r - c;
    for (double step = distance / std::sqrt(sharpness + 1.0) / 4.0; step < 2.0 * (light.size.x + light.size.y); step *= 4.0)
      peak_steps.push_back(step);
  }
  if (light.shape == AreaShape::rect) {
    const double half_w = light.size.x / 2.0, half_h = light.size.y / 2.0;
    const double foot_s = -glm::dot(c, u), foot_t = -glm::dot(c, v);  // where the point stands over the plane
    // Near the foot the integrand peaks with width h: pieces growing geometrically from it.
    std::vector<double> s_cuts = {foot_s}, t_cuts = {foot_t};
    for (double step = h; step < 2.0 * (half_w + half_h); step *= 8.0)
      for (double sign : {-1.0, 1.0}) {
        s_cuts.push_back(foot_s + sign * step);
        t_cuts.push_back(foot_t + sign * step);
      }
    if (!peak_steps.empty()) {
      const double peak_s = glm::dot(peak, u), peak_t = glm::dot(peak, v);
      s_cuts.push_back(peak_s);
      t_cuts.push_back(peak_t);
      for (double step : peak_steps)
        for (double sign : {-1.0, 1.0}) {
          s_cuts.push_back(peak_s + sign * step);
          t_cuts.push_back(peak_t + sign * step);
        }
    }
    for (const HalfPlane& side : sides)
      if (side.gu != 0.0)
        for (double t_edge : {-half_h, half_h}) s_cuts.push_back(-(side.base + side.gv * t_edge) / side.gu);
    double s_meet = 0.0, t_meet = 0.0;
    if (sides.size() == 2 && corner(sides[0], sides[1], s_meet, t_meet)) s_cuts.push_back(s_meet);
    for (bool highlight : {false, true}) {
      const glm::dvec3 total = integrate_pieces(-half_w, half_w, s_cuts, foot_s, order, [&](double s) {
        std::vector<std::pair<double, double>> lines;
        for (const HalfPlane& side : sides)
          if (highlight || &side == &sides[0]) lines.push_back({side.base + side.gu * s, side.gv});
        const auto [lo, hi] = upper_side(lines, -half_h, half_h);
        return integrate_pieces(lo, hi, t_cuts, foot_t, order, [&](double t) { return value(c + s * u + t * v, highlight); });
      });
      if (highlight) result.lobe = total;
      else result.irradiance = total.x;
    }
    return result;
  }
  // Disk: polar about its centre (dA = rho drho dphi), graded towards the centre; each edge crosses
  // the rim where a (gu cos + gv sin) = -base, and two edges meet at one angle.
  const double a = light.size.x / 2.0;
  std::vector<double> phi_cuts;
  auto add_angle = [&](double phi) { phi_cuts.push_back(phi - 2.0 * pi * std::floor(phi / (2.0 * pi))); };
  for (const HalfPlane& side : sides) {
    const double along = std::hypot(side.gu, side.gv);
    if (along > 0.0 && std::abs(side.base) < a * along) {
      const double centre = std::atan2(side.gv, side.gu), spread = std::acos(-side.base / (a * along));
      add_angle(centre - spread);
      add_angle(centre + spread);
    }
  }
  double s_meet = 0.0, t_meet = 0.0;
  if (sides.size() == 2 && corner(sides[0], sides[1], s_meet, t_meet) && std::hypot(s_meet, t_meet) < a)
    add_angle(std::atan2(t_meet, s_meet));
  std::vector<double> rho_cuts;
  // Cuts around a peak at `point` (on the emitter's plane, relative to its centre) at the given
  // distances from it: in rho, and in phi by the angle each subtends at the centre.
  auto add_focus = [&](const glm::dvec3& point, const std::vector<double>& steps) {
    const double focus_rho = std::hypot(glm::dot(point, u), glm::dot(point, v));
    const double focus_phi = std::atan2(glm::dot(point, v), glm::dot(point, u));
    rho_cuts.push_back(focus_rho);
    add_angle(focus_phi);
    for (double step : steps) {
      for (double sign : {-1.0, 1.0}) rho_cuts.push_back(focus_rho + sign * step);
      if (step < focus_rho)
        for (double sign : {-1.0, 1.0}) add_angle(focus_phi + sign * std::asin(step / focus_rho));
    }
  };
  // The point's foot on the plane, where every integrand peaks with width h: a point close to the
  // disk away from its centre sees that peak in both rho and phi (missed by 1.8% at h = 0.01
  // without these cuts).
  std::vector<double> foot_steps;
  for (double step = h; step < 2.0 * a; step *= 8.0) foot_steps.push_back(step);
  add_focus(-c - glm::dot(-c, normal) * normal, foot_steps);
  if (!peak_steps.empty()) add_focus(peak, peak_steps);
  for (bool highlight : {false, true}) {
    const glm::dvec3 total = integrate_pieces(0.0, 2.0 * pi, phi_cuts, -1.0, order, [&](double phi) {
      const double cosine = std::cos(phi), sine = std::sin(phi);
      std::vector<std::pair<double, double>> lines;
      for (const HalfPlane& side : sides)
        if (highlight || &side == &sides[0]) lines.push_back({side.base, side.gu * cosine + side.gv * sine});
      const auto [lo, hi] = upper_side(lines, 0.0, a);
      return integrate_pieces(lo, hi, rho_cuts, 0.0, order,
                              [&](double rho) { return rho * value(c + rho * (cosine * u + sine * v), highlight); });
    });
    if (highlight) result.lobe = total;
    else result.irradiance = total.x;
  }
  return result;
}

}  // namespace

Light area_shadow_light(const AreaLight& light) {
  Light centre;
  centre.type = LightType::point;
  centre.position = light.position;
  centre.color = light.color;
  centre.shadows = light.shadows;
  centre.group = light.group;
  return centre;
}

}  // namespace phongcl
