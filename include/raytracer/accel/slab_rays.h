// The ray/box arithmetic of the acceleration layer (bvh.h): a ray, or a bundle of rays,
// as the slab test takes it; the slab test of one box, and of a wide node's children;
// and the rays of a bundle's lanes, tried against an ellipsoid's box
// (ellipsoid_boxes.h) and then exactly. bvh.h states why each cull is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "raytracer/accel/bvh_build.h"
#include "raytracer/accel/exact_culling.h"
#include "raytracer/accel/intersect_lanes.h"
#include "raytracer/bit_scan.h"
#include "raytracer/compiler.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// A ray, or a bundle of rays, as the slab tests take it: per axis, two edges that
// hold the bundle's points at every t in [0, t1], the lower o_lo + t d_lo and the
// upper o_hi + t d_hi (one ray: both are the ray; interval arithmetic, as in
// S. Boulos et al., "Geometric and Arithmetic Culling Methods for Entire Ray
// Packets", University of Utah UUCS-06-010, 2006). A box [lo, hi] can be met only
// where the upper edge is >= lo and the lower edge <= hi: the upper edge passes lo at
// p = (lo - o_hi) / d_hi, from where on it is above lo if d_hi >= 0 (an entry), up
// to where if not (an exit); the lower edge passes hi at q = (hi - o_lo) / d_lo, an
// exit if d_lo >= 0, else an entry. The slab test takes [min, max] of p and q, which
// holds that interval where one is an entry and the other an exit (for one ray, the
// slab's two ends); where both are entries q is set to +inf, where both are exits p
// to -inf. An edge of zero slope exactly on a box's plane gives 0 * inf = NaN, which
// may cull the box: every ray of the bundle then stays on or outside that face, so
// outside the box's gap, where no root can be (as for one ray, bvh.h).
template <typename C>
struct SlabRay {
    C lo_from[3], lo_inv[3];  // for the box's low planes: o_hi, 1 / d_hi
    C hi_from[3], hi_inv[3];  // for its high planes: o_lo, 1 / d_lo
};

// Whether a direction's component d has no finite inverse though it is not 0: too small
// for one (a subnormal below about 5.6e-309 in double), or NaN. An infinite inverse
// makes a slab's t infinite where it is finite.
template <typename C>
RT_ALWAYS_INLINE bool unbounded_inverse(C d, C inv) {
    return d != 0 && !(std::abs(inv) <= std::numeric_limits<C>::max());
}

// The slab ray of a bundle's edges, or false where boxes may not cull its rays, which
// are then tried against every ellipsoid:
// - a direction has a component without a finite inverse (a subnormal scene: an
//   infinite inverse makes a slab's t infinite where it is finite);
// - some direction between the edges' may have every component below least in size
//   (Bvh's least_direction_; the edges of rays from one origin bound their directions,
//   those of a shadow bundle converge on its light): mapped into an ellipsoid's unit
//   space, d / s may then lie wholly below the normal range, where its components lose
//   the relative accuracy that the root solver's error bound assumes
//   (unit_sphere_roots.h), and the roots it reports may lie anywhere (float: a
//   direction of 2^-149 and a scale of 1.5).
template <typename C>
RT_ALWAYS_INLINE bool make_slab_ray(const C (&o_lo)[3], const C (&o_hi)[3], const C (&d_lo)[3],
                                    const C (&d_hi)[3], C least, SlabRay<C>& ray) {
    constexpr C kInf = std::numeric_limits<C>::infinity();
    bool long_enough = false;  // some axis where every direction's component is >= least
    for (int a = 0; a < 3; ++a) {
        // A shadow bundle's edges converge on its light (d_lo > d_hi once its points
        // spread wider than the slack; of opposite signs where the light lies between
        // their planes): its lanes' components lie between the two either way.
        const bool straddles = std::min(d_lo[a], d_hi[a]) <= 0 && std::max(d_lo[a], d_hi[a]) >= 0;
        long_enough = long_enough || (!straddles && std::min(std::abs(d_lo[a]), std::abs(d_hi[a])) >= least);
        // -0 as +0, so that a zero's sign follows the cases below.
        ray.lo_from[a] = o_hi[a], ray.lo_inv[a] = 1 / (d_hi[a] == 0 ? C(0) : d_hi[a]);
        ray.hi_from[a] = o_lo[a], ray.hi_inv[a] = 1 / (d_lo[a] == 0 ? C(0) : d_lo[a]);
        if (unbounded_inverse(d_hi[a], ray.lo_inv[a]) || unbounded_inverse(d_lo[a], ray.hi_inv[a]))
            return false;
        if (d_lo[a] < 0 && d_hi[a] >= 0) ray.hi_from[a] = -kInf, ray.hi_inv[a] = 1;  // q = +inf
        if (d_lo[a] >= 0 && d_hi[a] < 0) ray.lo_from[a] = kInf, ray.lo_inv[a] = 1;   // p = -inf
    }
    return long_enough;
}

// [enter, leave] clipped to one axis's slab, given its p and q (SlabRay). A slab's end is
// computed with at most 3 roundings, so the far end is widened by 2 gamma(3) (pbrt-v4,
// section 6.8.2).
template <typename C>
RT_ALWAYS_INLINE void clip_to_slab(C p, C q, C& enter, C& leave) {
    constexpr C kEps = std::numeric_limits<C>::epsilon() / 2;
    constexpr C kWiden = 1 + 2 * (3 * kEps / (1 - 3 * kEps));
    const C first = p < q ? p : q, last = (p < q ? q : p) * kWiden;
    enter = first > enter ? first : enter;
    leave = last < leave ? last : leave;
}

// Whether a ray from within every guard distance, or a bundle of them, may meet the
// box within [0, t1]: children_met()'s test for one box.
template <typename C>
RT_ALWAYS_INLINE bool meets_box(const SlabRay<C>& ray, const BuildBox<C>& box, C t1) {
    C enter = 0, leave = t1;
    for (int a = 0; a < 3; ++a)
        clip_to_slab((box.lo[a] - ray.lo_from[a]) * ray.lo_inv[a],
                     (box.hi[a] - ray.hi_from[a]) * ray.hi_inv[a], enter, leave);
    return enter <= leave;
}

// Whether a ray from within the box [o_lo, o_hi] is within every guard distance of the
// ellipsoids in bounds, the least of which is guard (nearly every ray in double: the
// scene is far smaller than the 1e10 smallest scales of BoxGaps::guard()), so that no
// node needs its guards checked.
template <typename C>
bool within_guard(const BuildBox<C>& bounds, C guard, const C (&o_lo)[3], const C (&o_hi)[3]) {
    C farthest = 0;
    for (int a = 0; a < 3; ++a)
        farthest = std::max({farthest, std::abs(bounds.lo[a] - o_lo[a]), std::abs(bounds.hi[a] - o_lo[a]),
                             std::abs(bounds.lo[a] - o_hi[a]), std::abs(bounds.hi[a] - o_hi[a])});
    return farthest <= guard;
}

// Whether a ray from `distance` (max-norm, to the box's farthest corner) beyond child k's
// guard may meet its box grown by rate times that distance (margin_per_reach()), plus
// 2 eps of each plane, so that the grown plane's own rounding stays outside the margin
// the roots need. Never culled where the margin is not a finite number, nor tried where
// it is over kUntriedSpread times the distance or kUntriedGrowth times the box's widest
// side: nearly every ray aimed near the box meets it then, and the test would only cost
// (docs/speed.md, "Rays from beyond the guards").
inline constexpr double kUntriedGrowth = 256, kUntriedSpread = 1.0 / 16;
template <typename C, int Width>
bool meets_grown_child(const WideNode<C, Width>& node, int k, const SlabRay<C>& ray, C t1, C distance) {
    constexpr C kEps = std::numeric_limits<C>::epsilon();
    if (!(node.rate[k] <= C(kUntriedSpread))) return true;
    const C margin = distance * node.rate[k];
    if (!(margin <= std::numeric_limits<C>::max())) return true;
    C widest = 0;
    for (int a = 0; a < 3; ++a) widest = std::max(widest, node.box[1][a][k] - node.box[0][a][k]);
    if (margin > C(kUntriedGrowth) * widest) return true;
    BuildBox<C> box;
    for (int a = 0; a < 3; ++a) {
        const C lo = node.box[0][a][k], hi = node.box[1][a][k];
        box.lo[a] = lo - (margin + 2 * kEps * std::abs(lo)),
        box.hi[a] = hi + (margin + 2 * kEps * std::abs(hi));
    }
    return meets_box(ray, box, t1);
}

// Which children of node the ray may meet within [0, t1] (bit k for child k), and where
// it enters each. The slabs are clipped at t = 0, not at the query's start, so that a
// box holding the origin is always met (the tangent roots of bvh.h): there each slab's
// near end is <= 0 and its far end >= 0, signs that the rounding of (plane - o) * inv
// keeps exactly. kGuarded: the ray's origin is known to be within every guard distance.
template <bool kGuarded, typename C, int Width>
RT_ALWAYS_INLINE unsigned children_met(const WideNode<C, Width>& node, const SlabRay<C>& ray, C t1,
                                       C (&near)[Width]) {
    C enter[Width], leave[Width], farthest[Width];
    for (int k = 0; k < Width; ++k) enter[k] = 0, leave[k] = t1, farthest[k] = 0;
    for (int a = 0; a < 3; ++a) {
        const C* lo = node.box[0][a];
        const C* hi = node.box[1][a];
        const C lo_from = ray.lo_from[a], lo_inv = ray.lo_inv[a];
        const C hi_from = ray.hi_from[a], hi_inv = ray.hi_inv[a];
        RT_VECTOR_LOOP
        for (int k = 0; k < Width; ++k) {
            const C to_lo = lo[k] - lo_from, to_hi = hi[k] - hi_from;
            clip_to_slab(to_lo * lo_inv, to_hi * hi_inv, enter[k], leave[k]);
            if (kGuarded) continue;
            const C reach = std::max(std::abs(to_lo), std::abs(to_hi));  // one ray only
            farthest[k] = reach > farthest[k] ? reach : farthest[k];
        }
    }
    unsigned mask = 0;
    RT_VECTOR_LOOP
    for (int k = 0; k < Width; ++k) {
        const bool met = enter[k] <= leave[k] || (!kGuarded && farthest[k] > node.guard[k]);
        mask |= met ? 1U << k : 0U;
        near[k] = kGuarded || farthest[k] <= node.guard[k] ? enter[k] : C(0);
    }
    if (!kGuarded)  // a child beyond its guard: its box grown for the ray's distance
        for (unsigned m = mask & node.used; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            if (farthest[k] > node.guard[k] && !meets_grown_child(node, k, ray, t1, farthest[k]))
                mask &= ~(1U << k);
        }
    return mask & node.used;
}

// The rays of a bundle's lanes, by axis and lane, each to be met within [0, t1[k].
// Written by set() alone, every lane: not zeroed first (a few KB a tile).
template <typename Real, int N>
struct LaneRays {
    using C = AtLeastDouble<Real>;
    using V = Vec3<Real>;

    Real from[3][N], along[3][N];  // the rays as given, for intersect_lanes() and the prefilter
    C inv[3][N], t1[N];            // for the slab tests
    unsigned unculled;             // lanes always met: a direction without a finite inverse

    // Lane k of lanes: origins[k] + t directions[k] for t in [0, end]; the other lanes'
    // rays zero (their inverses infinite; their answers are dropped). The lanes' rays are
    // gathered, then the inverses found for all lanes at once (vector divisions).
    void set(const V (&origins)[N], const V (&directions)[N], unsigned lanes, C end) {
        for (int k = 0; k < N; ++k) {
            const bool in = (lanes >> k & 1U) != 0;
            const V& o = origins[k];
            const V& d = directions[k];
            from[0][k] = in ? o.x : 0, from[1][k] = in ? o.y : 0, from[2][k] = in ? o.z : 0;
            along[0][k] = in ? d.x : 0, along[1][k] = in ? d.y : 0, along[2][k] = in ? d.z : 0;
            t1[k] = in ? end : 0;
        }
        unsigned unbounded = 0;
        for (int a = 0; a < 3; ++a) {
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k) {
                inv[a][k] = 1 / C(along[a][k]);
                unbounded |= unbounded_inverse(C(along[a][k]), inv[a][k]) ? 1U << k : 0U;
            }
        }
        unculled = unbounded & lanes;
    }
    // Which of lanes may meet e's box (inflated_box()); where some do, every lane's
    // roots with e, in one vector loop (intersect()'s, bit for bit).
    unsigned roots(const Ellipsoid<Real>& e, const BuildBox<C>& box, unsigned lanes, Real (&hit)[N],
                   Real (&near)[N], Real (&far)[N]) const {
        const unsigned met = lanes & meeting(box);
        if (met == 0) return met;
        intersect_lanes<N>(e, from[0], from[1], from[2], along[0], along[1], along[2], hit, near, far);
        return met;
    }
    // The lanes whose guarded ray may meet the box, all lanes in one vector loop.
    unsigned meeting(const BuildBox<C>& box) const {
        C enter[N], leave[N];
        for (int k = 0; k < N; ++k) enter[k] = 0, leave[k] = t1[k];
        for (int a = 0; a < 3; ++a) {
            const C lo = box.lo[a], hi = box.hi[a];
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k)
                clip_to_slab((lo - C(from[a][k])) * inv[a][k], (hi - C(from[a][k])) * inv[a][k], enter[k],
                             leave[k]);
        }
        unsigned mask = unculled;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) mask |= enter[k] <= leave[k] ? 1U << k : 0U;
        return mask;
    }
};

// Whether the directions of a bundle of rays from different origins, per axis within
// [d_lo, d_hi], are close enough for its descent to pay (Bvh::closest() for lanes): at
// least kNarrowLanes rays whose directions differ by at most kNarrowSpread of their
// largest component. Measured (callgrind, whole runs, one thread): sphereflakes 3 / 4 / 5
// 7.3% / 5.6% / 2.3% fewer instructions, the random scenes within 0.1%; a spread of 0.3
// was as good on sphereflakes 3 and 4 but 1.4% worse on 5, one of 1 worse everywhere.
inline constexpr int kNarrowLanes = 4;
inline constexpr double kNarrowSpread = 0.1;
template <typename C>
bool narrow_directions(const C (&d_lo)[3], const C (&d_hi)[3], unsigned lanes) {
    C spread = 0, largest = 0;
    for (int a = 0; a < 3; ++a)
        spread = std::max(spread, d_hi[a] - d_lo[a]),
        largest = std::max({largest, std::abs(d_lo[a]), std::abs(d_hi[a])});
    return bit_count(lanes) >= kNarrowLanes && spread <= C(kNarrowSpread) * largest;
}

// Per axis, the least and the greatest of v[k] over the lanes (a NaN is passed over by
// std::min and std::max: a ray with a NaN has no visible root to lose). Kept in locals, not in
// lo and hi, which may alias v: through memory each lane waited on the last one's
// stores (a sixth of a course scene's time through the tree).
template <typename C, typename Real, int N>
RT_ALWAYS_INLINE void bounds_of(const Vec3<Real> (&v)[N], unsigned lanes, C (&lo)[3], C (&hi)[3]) {
    constexpr C kInf = std::numeric_limits<C>::infinity();
    C x_lo = kInf, y_lo = kInf, z_lo = kInf, x_hi = -kInf, y_hi = -kInf, z_hi = -kInf;
    for (unsigned m = lanes; m != 0; m &= m - 1) {
        const Vec3<Real>& p = v[lowest_bit(m)];
        const C x = C(p.x), y = C(p.y), z = C(p.z);
        x_lo = std::min(x_lo, x), y_lo = std::min(y_lo, y), z_lo = std::min(z_lo, z);
        x_hi = std::max(x_hi, x), y_hi = std::max(y_hi, y), z_hi = std::max(z_hi, z);
    }
    lo[0] = x_lo, lo[1] = y_lo, lo[2] = z_lo, hi[0] = x_hi, hi[1] = y_hi, hi[2] = z_hi;
}

// The edges of a bundle of shadow rays from points[k] (k in lanes) to one light, for
// make_slab_ray(): per axis, origins within [o_lo, o_hi] and directions within [d_lo,
// d_hi]. The edges converge on the light: point + t (light - point) is
// (1 - t) point + t light, so for 0 <= t <= 1 each coordinate lies between
// o_lo + t (light - o_lo) and o_hi + t (light - o_hi), widened by the rounding of
// to_light and of those differences (a few ulps of |light| + |point|): bounds true on
// their own, though the boxes' gaps (exact_culling.h) hold that rounding over a
// thousand times, so no image changes without it.
template <typename C, typename Real, int N>
RT_ALWAYS_INLINE void shadow_bundle_edges(const Vec3<Real> (&points)[N], const Vec3<Real>& light,
                                          unsigned lanes, C (&o_lo)[3], C (&o_hi)[3], C (&d_lo)[3],
                                          C (&d_hi)[3]) {
    bounds_of(points, lanes, o_lo, o_hi);
    const C to[3] = {C(light.x), C(light.y), C(light.z)};
    for (int a = 0; a < 3; ++a) {
        const C slack =
            4 * C(scene_epsilon<Real>()) * (std::abs(to[a]) + std::max(std::abs(o_lo[a]), std::abs(o_hi[a])));
        d_lo[a] = (to[a] - o_lo[a]) - slack, d_hi[a] = (to[a] - o_hi[a]) + slack;
    }
}

}  // namespace rt
