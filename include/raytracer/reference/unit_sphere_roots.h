// The one root solver: where a mapped ray o' + t d' meets the unit sphere (ellipsoid.h
// maps an ellipsoid's ray there). It is one lane's arithmetic, written once and without
// branches (selects only), so that a scalar call is one lane and a loop calling it over
// lanes of arrays is vectorised by GCC and Clang with the same IEEE operations in the
// same order: intersect_mapped() (one lane), intersect_lanes() (N lanes) and
// merge_eye_row() (a run of eye rays' columns, eye_block.h) get the same bits (the build
// uses -ffp-contract=off).
//
// Scaling. d' is scaled first, e = d' / m with m the power of two at or below
// max |d'_i| (exact; long double takes m = max |d'_i|, its reciprocal rounded far below
// the scene's eps), so that |e| is in [1, 2 sqrt(3)) and
// no square of it overflows or underflows (a thickness of 1e-300 makes d'_z ~ 1e300).
// The ray is o' + s e with s = t / m; a = e.e, b = o'.e, c = o'.o' - 1, and
// a s^2 + 2 b s + c = 0. No square of o' is needed for the decision: with w = o' x e,
// b^2 - a c = a - w.w (|w| / |e| is the distance of the line from the centre, and
// |w| <= |o'| |e|); where w.w overflows the ray misses by far.
//
// Discriminant. w / |e| is the vector l = o' - (o'.u) u, u = e / |e|, of E. Haines,
// J. Guenther, T. Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection"
// (Ray Tracing Gems, Apress 2019, ch. 7), but as a cross product it does not cancel
// where o' is long and nearly along e (a thin or far ellipsoid seen face on, where l's
// component along u is |o'| minus |o'|): each component o'_j e_k - o'_k e_j is a
// difference of two products whose size, m_i = |o'_j e_k| + |o'_k e_j|, is a
// world-space distance over a scale, not |o'|.
//
// Error bound, with eps = epsilon (2u, u the unit roundoff), first order in eps
// (N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002,
// sections 2.2 and 3.1): the data o' and e carry relative errors of at most 2 eps per
// component (o' = (o - C)/s: the roundings of the scene's own numbers and of the
// arithmetic; e: d/s and the scaling), so each product o'_j e_k is off by at most
// 4.5 eps of itself (2 + 2 from its factors, eps/2 its own rounding), and the
// difference by eps/2 of |w_i| <= m_i more: |dw_i| <= 5 eps m_i. Then |d(w.w)| <=
// 2 sum |w_i| |dw_i| + 1.5 eps w.w <= 10 eps sum |w_i| m_i + 1.5 eps w.w (the squares'
// and sums' roundings), a = e.e is off by at most 5.5 eps a (4 eps from e, 1.5 its
// own), and the difference a - w.w by eps/2 (a + w.w) more. A value of a - w.w
// computed within
//   bound = eps (10 sum |w_i| m_i + 2 w.w + 6 a)
// (computed as 2 eps (5 sum + w.w + 3 a), a multiply fewer) below zero cannot be told
// from zero and counts as tangent (an exactly tangent ray is a hit, SPEC section 4);
// eps is the scene's precision (scene_precision.h), so double and long double decide
// alike. A ray that passes farther than twice the radius (w.w > 4a) is a miss whatever
// the bound says: the bound only concerns near-tangent rays. For an eye ray through a
// facing disc m_i is a few of its radii, so the bound is a few eps, not eps |o'|; it is
// eps |o'| where o' is long and across the ray (a sphere far off the axis), as the
// data's own rounding is there.
//
// Roots. q = -(b + sign(b) sqrt(a - w.w)) is free of cancellation, and s = q/a, s = c/q
// (W. H. Press et al., Numerical Recipes, 3rd ed., section 5.6; D. Goldberg, "What Every
// Computer Scientist Should Know About Floating-Point Arithmetic", ACM Computing Surveys
// 23(1), 1991, section 1.4), both from one reciprocal r = 1/(a q): q/a = q (q r) and
// c/q = c (a r) (three roundings each). Where c >= 1e30
// (it may have overflowed) |b| >= 1e15 |e| >> sqrt(a - w.w), and the other root is
// -(b - sign(b) sqrt(a - w.w)) / a, without cancellation. q = 0 (the origin on the
// surface, the ray grazing it) gives roots 0, 0.
//
// The origin on the surface. A shadow or mirrored ray starts where the last ray met
// the surface, so c = o'.o' - 1 is 0 but for its rounding, at most about 5.5 eps:
// 4.5 eps of each square (2 + 2 from o'_i, eps/2 its own), eps/2 of each sum, and the
// subtraction exact (Sterbenz) for o'.o' near 1. The root c/q is then that rounding
// over |q| m, in t: eps times the ellipsoid's size over the ray's length. For a floor of
// radius 1e12 under a ray a few units long, or a mirror room seen through a window 1e-9
// wide (a ray 1e-9 long), that is 1e-4 or more, past the mirrored rays' 0.0001 and the
// shadow rays' 0.001: the ray met its own surface again (double and long double
// differed in half the pixels of scenes/hard/own_root_*.txt). Where |c| is within
// about twice its rounding (12 eps), the origin is on the surface, as in exact
// arithmetic, and its root is 0 exactly: the thresholds discard it. The other root,
// q/a, does not use c.
//
// The point at t = 1. Where a decimal scene puts a root exactly at t = 1 (an eye ray's
// pixel on the near plane lying on the surface, a light on a surface), the computed root
// can be far more than a few ulps from 1 when the ray meets the surface at a slant (a
// small discriminant amplifies its error), so comparing it with 1 would decide by
// rounding, and differently in double and long double. Whether the point itself lies on
// the surface is well conditioned: p = o' + d' with |dp_i| <= 2.5 eps g_i,
// g_i = |o'_i| + |d'_i| (2 eps from o' and d', eps/2 the sum's rounding), so |p|^2 - 1
// is off by at most 5 eps sum |p_i| g_i + 2 eps (its own evaluation: about 2.5 eps of
// the smaller squares, computed as below); within twice that of zero, p is on the
// surface, the ray meets it (a hit) and the root nearer t = 1 is 1 exactly: thresholds at
// t = 1 (the near plane, the light) then decide as in exact arithmetic, alike in every
// precision where p is exact (a decimal scene's round numbers) and otherwise but within
// p's own rounding of the allowance. Where that allowance is not small (|p| near
// overflow) nothing is set.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "raytracer/compiler.h"
#include "raytracer/scene_precision.h"

namespace rt {

// A power of two p with 1 <= p |x| < 2 for a finite x != 0 (|x| below the normal range
// is taken as the smallest normal): scaling by it is exact. Read from the exponent bits
// (IEEE 754 binary64 and binary32) so that it vectorises. Other formats (long double)
// get 1 / |x| itself, rounded: not a power of two, but its rounding (2^-64) is far
// below the double ulps the error bounds allow for e.
template <typename Real>
RT_ALWAYS_INLINE Real reciprocal_power_of_two(Real x) {
    using std::abs;
    if constexpr (std::numeric_limits<Real>::is_iec559 && sizeof(Real) == sizeof(std::uint64_t) &&
                  std::numeric_limits<Real>::digits == 53) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        const std::uint64_t exponent = bits & 0x7FF0000000000000U;
        // Biased exponent k: 2^(k - 1023), reciprocal 2^(1023 - k), biased 2046 - k.
        const std::uint64_t inverse = exponent == 0 ? 0x7FD0000000000000U : 0x7FE0000000000000U - exponent;
        Real p;
        std::memcpy(&p, &inverse, sizeof p);
        return p;
    } else if constexpr (std::numeric_limits<Real>::is_iec559 && sizeof(Real) == sizeof(std::uint32_t) &&
                         std::numeric_limits<Real>::digits == 24) {
        std::uint32_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        const std::uint32_t exponent = bits & 0x7F800000U;
        const std::uint32_t inverse = exponent == 0 ? 0x7E800000U : 0x7F000000U - exponent;
        Real p;
        std::memcpy(&p, &inverse, sizeof p);
        return p;
    } else {
        return Real(1) / abs(x);
    }
}

// The first half: whether the line meets the sphere, and the terms the roots need.
template <typename Real>
struct UnitLine {
    Real hit;              // 1 or 0
    Real on;               // 1 where the point at t = 1 is on the surface (then hit is 1)
    Real a, b, disc;       // e.e, o'.e, a - w.w (clamped at 0)
    Real inverse_largest;  // 1/m
};

// o' = (ox, oy, oz), d' = (dx, dy, dz).
template <typename Real>
RT_ALWAYS_INLINE UnitLine<Real> unit_line(Real ox, Real oy, Real oz, Real dx, Real dy, Real dz) {
    using std::abs;
    // e = d' / m. std::max is not used: (x < y) ? y : x vectorises.
    const Real ax = abs(dx), ay = abs(dy), az = abs(dz);
    const Real ayz = ay < az ? az : ay;
    const Real inverse_largest = reciprocal_power_of_two(ax < ayz ? ayz : ax);
    const Real ex = dx * inverse_largest, ey = dy * inverse_largest, ez = dz * inverse_largest;
    const Real a = ex * ex + ey * ey + ez * ez;
    const Real b = ox * ex + oy * ey + oz * ez;
    // w = o' x e and the sizes m_i of its components' products.
    const Real pyz = oy * ez, pzy = oz * ey, pzx = oz * ex, pxz = ox * ez, pxy = ox * ey, pyx = oy * ex;
    const Real wx = pyz - pzy, wy = pzx - pxz, wz = pxy - pyx;
    const Real mx = abs(pyz) + abs(pzy), my = abs(pzx) + abs(pxz), mz = abs(pxy) + abs(pyx);
    const Real w2 = wx * wx + wy * wy + wz * wz;
    const Real disc = a - w2;
    const Real bound = (Real(2) * scene_epsilon<Real>()) *
                       (Real(5) * (abs(wx) * mx + abs(wy) * my + abs(wz) * mz) + w2 + Real(3) * a);
    const Real miss = disc < -bound ? Real(1) : (w2 > Real(4) * a ? Real(1) : Real(0));
    // The point at t = 1.
    const Real px = ox + dx, py = oy + dy, pz = oz + dz;
    const Real gx = abs(ox) + ax, gy = abs(oy) + ay, gz = abs(oz) + az;
    // |p|^2 - 1 as (k - 1)(k + 1) + the other two squares, k the largest |p_i|: k - 1 is
    // exact (Sterbenz) where |p| is near 1. |p|^2 rounded first is a multiple of eps or
    // eps/2 there, which would snap values near the allowance onto it: decided by rounding.
    const Real kx = abs(px), ky = abs(py), kz = abs(pz), sx = px * px, sy = py * py, sz = pz * pz;
    const bool x_largest = kx >= ky && kx >= kz, y_largest = ky > kx && ky >= kz;
    const Real k = x_largest ? kx : (y_largest ? ky : kz);
    const Real others = x_largest ? sy + sz : (y_largest ? sx + sz : sx + sy);
    const Real surface = (k - Real(1)) * (k + Real(1)) + others;
    const Real allowance =
        scene_epsilon<Real>() * (Real(10) * (abs(px) * gx + abs(py) * gy + abs(pz) * gz) + Real(4));
    const Real on = abs(surface) <= allowance ? (allowance < Real(0.5) ? Real(1) : Real(0)) : Real(0);
    return {on != 0 ? Real(1) : Real(1) - miss, on, a, b, disc < 0 ? Real(0) : disc, inverse_largest};
}

// Both ray parameters t of the original ray where it meets the surface, near <= far,
// where hit is 1 (the line meets the sphere, tangency included); else hit is 0. A number
// rather than a bool, so that a loop over lanes stays in vector instructions.
template <typename Real>
struct Roots {
    Real hit, near, far;
};

// The second half, given unit_line() and c = o'.o' - 1 of the origin (MappedOrigin).
template <typename Real>
RT_ALWAYS_INLINE Roots<Real> unit_roots(const UnitLine<Real>& line, Real c) {
    using std::abs;
    const Real signed_root = std::copysign(std::sqrt(line.disc), line.b);
    const Real q = -(line.b + signed_root);
    const Real r = Real(1) / (line.a * q);
    const Real q_r = q * r, a_r = line.a * r;  // 1/a and 1/q
    // The origin on the surface: its root is 0 exactly.
    const Real origin_c = abs(c) <= Real(12) * scene_epsilon<Real>() ? Real(0) : c;
    const Real other = c < Real(1e30) ? origin_c * a_r : -(line.b - signed_root) * q_r;
    const Real t1 = (q * q_r) * line.inverse_largest, t2 = other * line.inverse_largest;
    Real near = t1 > t2 ? t2 : t1, far = t1 > t2 ? t1 : t2;
    near = q == 0 ? Real(0) : near;
    far = q == 0 ? Real(0) : far;
    // The root nearer t = 1 is 1 where the point at t = 1 is on the surface.
    const Real near_at_one = abs(near - Real(1)) <= abs(far - Real(1)) ? line.on : Real(0);
    near = near_at_one != 0 ? Real(1) : near;
    far = line.on - near_at_one != 0 ? Real(1) : far;
    return {line.hit, near, far};
}

// Both halves: one lane, o' = (ox, oy, oz), c = o'.o' - 1, d' = (dx, dy, dz).
template <typename Real>
RT_ALWAYS_INLINE Roots<Real> unit_sphere_roots(Real ox, Real oy, Real oz, Real c, Real dx, Real dy, Real dz) {
    return unit_roots(unit_line(ox, oy, oz, dx, dy, dz), c);
}

}  // namespace rt
