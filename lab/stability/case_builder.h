#pragma once
// What the catalogue's files share: a starting scene, the way a case is completed (oracle values,
// absolute floor) and the tolerances, each justified once here.
#include <limits>
#include <string>

#include "stability/gbuffer_builder.h"
#include "stability/stability_case.h"

namespace phongcl {

// The G-buffer values the catalogue's hostile cases write.
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();

// Eye at the origin, so rebasing positions on the host is exact and the kernel sees exactly the
// floats the case wrote; no ambient, no lights; material 0 is (ka, kd, ks, q).
Scene starting_scene(double ka, double kd, double ks, double shininess);

// A case name's number: "1e-20", "179.999" (%g).
std::string number(double value);

// Fills exact (the oracle, pixel by pixel) and abs_floor (1e-6 of the brightest light or ambient
// colour, since shading is linear in them) unless the case set a smaller floor already.
StabilityCase complete(StabilityCase c);

// Sets c.across from the oracle on each of `moved`: the case's scene with an edge moved by the
// kernel's rounding (StabilityCase::across), on a step edge or a continuous one.
StabilityCase with_edge(StabilityCase c, const std::vector<Scene>& moved, bool step);

// --- Tolerances. u = 2^-24 = 6e-8, the float rounding unit. `amplification` is the case's
// condition number (1 for plain shading; stiff_amplification for x^q): each variant's bound is a
// base for the fixed chain of operations plus 16 rounding units times the amplification (a few
// roundings feed the amplified quantity; 16 leaves a factor of about 4 over them).

// How far the kernel's rounding can move an edge of F = falloff * window * cone. d / R carries
// ~6 u (|toward|^2, rsqrt's 2 ulp, the products, 1 / R rounded to float); the cone's off-axis
// angle theta ~3 u relative (1 - c from |-l - a|^2 / 2, its three roundings) plus ~u absolute
// per component of l and of the axis rounded to float. With 16 u relative and 4 u absolute, a
// range edge moves by R * kEdgeRelative, a cone's by theta * kEdgeRelative + kEdgeAbsolute.
constexpr double kEdgeRelative = 16 * 0x1p-24;
constexpr double kEdgeAbsolute = 4 * 0x1p-24;

// The double reference: rounds its result to float (u), and takes pow(v.r, q) directly, so at
// v.r near 1 it has fast's amplification with the double unit 2^-53 in place of u.
Expectation reference_expectation(double direct_amplification = 1.0);

// double: the same float inputs, double arithmetic; what remains is the float rounding of the
// host's packing (positions relative to the eye, directional l; exact in the cases that put the
// eye at the origin) and of the result.
// `packing_amplification` is what the float rounding of the packed inputs is amplified by (0 where
// the case makes them exact), `amplification` what the double arithmetic's own rounding is.
Expectation double_expectation(double amplification = 1.0, double packing_amplification = 0.0);

// precise: float arithmetic, log and exp as polynomials good to about 1 ulp. A shaded value is a
// chain of ~20 float operations (normalise ~3 u per component, dot products ~2 u, one log and one
// exp), ~30 u = 2e-6; the base 1e-5 leaves a factor of 5.
Expectation precise_expectation(double amplification = 1.0);

// fast: -cl-fast-relaxed-math on the same formulas as precise (1 - v.r from |v - r|^2 / 2, inline
// log and exp, rescaled normalisation), which the compiler may reassociate and contract: base 1e-4
// on precise's amplification.
Expectation fast_expectation(double amplification = 1.0);

// half-storage: the G-buffer planes are rounded to half (relative 2^-11 = 4.9e-4) before the same
// float math as precise. Where every value the case stores is exact in half (small integers,
// powers of two) that rounding is nothing and precise's bound holds; otherwise `inexact` applies.
Expectation half_expectation(const GBuffer& gbuffer, double amplification, const Expectation& inexact);

// x^q's condition number for the precise arithmetic: a relative error e in x (x < 0.5, where the
// kernel takes log x) or in 1 - x (x >= 0.5, where it takes log1p of -(1 - x) = -|v - r|^2/2)
// moves the result by q |ln x| e, or q e for small x. Results below 1e-6 are measured against the
// absolute floor, so the amplification shrinks with them.
double stiff_amplification(long double x, double shininess);
// A highlight's condition number for direction errors: an error e (radians) in v, l or n moves
// the exponent q |v - r|^2 / 2 by q |v - r| e, twice that for n (r turns twice as fast). Where the
// highlight is above the floor (exponent < 14), |v - r| < sqrt(28 / q): at most 2 sqrt(28 q) e.
double highlight_amplification(double shininess);
// The same for an evaluation that takes log x from x itself (the reference's pow, in double): an
// absolute error u in x is q u / x.
double direct_pow_amplification(long double x, double shininess);

}  // namespace phongcl
