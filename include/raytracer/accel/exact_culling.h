// What the fast paths may skip without changing a byte of the reference's image: the
// gap a bounding volume keeps around its ellipsoid, the reach within which that holds,
// and the shadow tests that the ellipsoid a ray starts on never needs. Shared by the
// tree (accel/) and the flat sweep (flat_sweep/); the reference (reference/) skips
// nothing.
#pragma once

#include <cmath>
#include <limits>

#include "raytracer/compiler.h"
#include "raytracer/lanes.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/vec3.h"

namespace rt {

// What a bounding volume may cull (docs/speed.md, "Why every path gives the reference's
// bytes"), the argument stated once. A root the solver reports lies within its rounding
// of the unit sphere: a few ulps of |o'| away from tangency, and at most about
// 110 eps (1 + |o'|) for a ray that only touches it (the clamped discriminant: bvh.h).
// A bounding volume that holds its ellipsoid with a gap of kCullingGap in the unit
// sphere's space (the flat sweep's spheres, the tree's boxes) therefore rules out only
// tests that would find no usable root, for rays from within a reach where that
// rounding stays inside the gap; beyond it, only by a volume grown for the ray's
// distance (the tree's boxes: margin_per_reach()).
inline constexpr double kCullingGap = 1e-3;
// The silhouette tests (silhouette.h, screen_bounds.h) square an eye ray's direction in
// an ellipsoid's unit space: from this size on, its squares and their products with
// terms of |o'| <= 1000 stay far above the end of double's normal range (1e-308); below
// it (a window 1e100 times smaller than the ellipsoid) they may underflow to 0, and no
// row is ruled out.
inline constexpr double kLeastSquaredDirection = 1e-100;
// The flat sweep's reach, in smallest scales: the bound above is 2.4e-8 at 1e6 in
// double. In float it is 1.3e-3 at 1e2, about the gap itself; the bound is loose (the
// adversarial rays of speed.accel at 49-51 smallest scales find no difference) and
// float renders only for the tests and the precision report.
template <typename Real>
constexpr double culling_reach() {
    return std::numeric_limits<Real>::digits > 30 ? 1e6 : 1e2;
}
// The tree's: a gap of gap_per_reach() |o'| holds the bound twice over in double (and in
// long double, whose rounding is smaller), so a box grown by kCullingGap culls rays from
// within 2e10 smallest scales, and one grown more from farther (BoxGaps, ellipsoid_boxes.h);
// float keeps the flat sweep's reach. (speed.accel's adversarial rays find no difference
// even at 1e-16, where the bound is 240 times the gap at the reach: the rounding seen is
// far below it, and the bound, not what a test happened to find, sets the reach.)
template <typename Real>
constexpr double gap_per_reach() {
    return std::numeric_limits<Real>::digits > 30 ? 2 * 110 * std::numeric_limits<double>::epsilon()
                                                  : kCullingGap / culling_reach<Real>();
}
// The most a tree's box is grown, in the unit sphere's space: twice its ellipsoid.
inline constexpr double kLargestCullingGap = 1;
// Beyond its guard, a box still culls a ray from max-norm distance D once grown on each
// side by D times this and the largest aspect (largest over smallest scale) of the
// ellipsoids in it. For each of them, either D is within its own guard, where its box
// already suffices, or D > guard > 50 smallest scales, where the roots' bound
// 110 eps (1 + |o'|), with |o'| <= sqrt(3) D / smallest < 2 D / smallest, is
// 220 eps D / smallest in the unit sphere's space, at most 220 eps D aspect in the world
// on any axis; held twice over, which also covers the rounding of the grown box's
// planes (meets_grown_child()).
template <typename Real>
constexpr double margin_per_reach() {
    return 2 * 220 * static_cast<double>(std::numeric_limits<Real>::epsilon());
}

// Whether the ellipsoid a shadow ray starts on cannot block it, so that
// blocks_segment() need not be asked. From a point seen from outside, towards a light in
// front (N.L > 0), the ray leaves the ellipsoid at once, and the ellipsoid is convex:
// intersect() finds a root below 0 and one within |c| / b of 0, where c = o'.o' - 1 (0
// but for rounding; as mapped_origin() computes it) and b = o'.d' >= |(P - C)/s^2|
// |L - P| (N.L - 32 eps) (Cauchy-Schwarz on the rounding of each factor). Where that
// bound exceeds 2000 |c| (2 / kShadowRayMinT), neither root is in (0.001, 1). The
// caller asks only for points seen from outside; false where |c| is NaN. For one ray
// or lanes (lanes.h: T = Lanes).
template <typename Real, typename T>
MaskOf<T> leaves_own_ellipsoid(const T& scaled_length, const T& distance, const T& n_dot_l, const T& abs_c) {
    const T slack = T(Real(32) * std::numeric_limits<Real>::epsilon());
    return scaled_length * distance * (n_dot_l - slack) > T(Real(2000)) * abs_c;
}

// |c| of leaves_own_ellipsoid() at a point on the ellipsoid of this centre and scale, as
// intersect() computes c (mapped_point()). For one ray or lanes.
template <typename T>
RT_ALWAYS_INLINE T own_abs_c(const Vec3<T>& point, const Vec3<T>& centre, const Vec3<T>& scale) {
    using std::abs;
    return abs(mapped_point(point, centre, scale).c);
}

}  // namespace rt
