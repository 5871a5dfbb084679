// The acceleration layer: a bounding volume hierarchy over the ellipsoids' boxes, with the queries of
// brute_force.h (closest hit, any hit) in time that grows like log N.
//
// The tree is built binary and collapsed into nodes of Width children (bvh_build.h), whose boxes are stored
// as structure of arrays and tested against a ray in one loop over the lanes that the compiler turns into
// vector instructions (8 doubles, one AVX-512 register or two AVX2 ones, measured faster here than 4):
// Embree's BVH4/BVH8 (I. Wald et al., "Embree: A Kernel Framework for Efficient CPU Ray Tracing", ACM TOG
// 33(4), 2014). The closest-hit query visits children nearest first and skips a subtree that starts beyond
// the nearest root found so far; the any-hit query takes them in any order and stops at the first blocker.
//
// Exactness: a query returns what brute_force.h returns, bit for bit. Each ellipsoid's box is its
// axis-aligned bounding box grown by at least kCullingGap of each scale (exact_culling.h, ellipsoid_boxes.h),
// a gap of 1e-3 in the unit sphere's space; a root that intersect() reports lies within a few ulps of |o'| of
// the unit sphere (the rounding of the mapped origin, plus the tangency allowance, unit_sphere_roots.h), so
// its point lies deep inside the box, and the slab test's own rounding (a few ulps of the box's distance)
// cannot move it out. A ray that runs in a slab's plane, where the slab test's 0 * inf is NaN, cannot reach a
// box's inside at all. Both hold only while the ray's origin is within the reach its box's gap holds
// (BoxGaps, ellipsoid_boxes.h: |o'| <= 2e10 in double for the gap of 1e-3, the roots' rounding 5e-4 there; an
// ellipsoid thin beside its scene is grown more, so that its box culls rays from anywhere in it): a child is
// culled for a ray from within the guard distance of every ellipsoid under it, and for one from farther by
// its box grown for the ray's distance (margin_per_reach(), children_met(); lone rays: a bundle from there
// goes ray by ray); a leaf's ellipsoids are then all solved. A
// child whose box holds the ray's origin is never culled either: from a point on the surface (|o'| = 1 within
// rounding) along its tangent plane, o'.d' is a rounding residue, and where intersect() clamps the
// discriminant to zero (the tangency allowance) its second root c/q is c / |o'.d'|, anywhere along the ray,
// far outside the box (a shadow ray towards a light 2000 radii away leaves the box before t = 0.001 and is
// still "blocked" at t ~ 0.5). From outside the box, |o'.d'| / |d'| >= sqrt(1.001^2 - 1) ~ 0.045 bounds that
// root's distance from the tangent point to ~110 eps (1 + |o'|), inside the gap (half of it at the farthest
// reach, exact_culling.h; a box grown by more than kCullingGap has sqrt((1 + gap)^2 - 1) there, and a smaller
// bound). The ellipsoids of a leaf are always tried with the exact intersect(). Ties between equal roots go
// to the lower index (NearestHit::replaced_by()).
//
// Memory: the tree and the ellipsoids in leaf order; a query uses a fixed stack, the same for any scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/accel/bvh_build.h"
#include "raytracer/accel/cleared_lanes.h"
#include "raytracer/accel/ellipsoid_boxes.h"
#include "raytracer/accel/eye_block.h"
#include "raytracer/accel/shadow_prefilter.h"
#include "raytracer/accel/slab_rays.h"
#include "raytracer/bit_scan.h"
#include "raytracer/large_pages.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real, int Width = 8>
class Bvh {
public:
    using V = Vec3<Real>;
    using C = AtLeastDouble<Real>;  // boxes and slab tests
    static_assert(Width >= 2 && Width <= 16, "a node holds 2 to 16 children");

    // Over ellipsoid_of(i) for i < count, made where needed (for its box, then in leaf
    // order beside the collapse). threads: how many may build the tree (1 or 2 are used).
    template <typename EllipsoidOf>
    Bvh(std::size_t count, EllipsoidOf ellipsoid_of, unsigned threads = 1);
    explicit Bvh(const std::vector<Ellipsoid<Real>>& ellipsoids, unsigned threads = 1)
        : Bvh(
              ellipsoids.size(), [&ellipsoids](std::size_t i) { return ellipsoids[i]; }, threads) {}

    // As BruteForce::closest(): the nearest visible root beyond min_t.
    NearestHit<Real> closest(const V& origin, const V& direction, double min_t) const {
        const Real beyond = visible_beyond(Real(min_t));
        const OneRay ray = one_ray(origin, direction);
        NearestHit<Real> best;
        traverse<Visit::NearestFirst>(ray, std::numeric_limits<C>::infinity(), [&](Child leaf, C& t1) {
            for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k)
                if (best.offer(intersect(ellipsoids_[k], origin, direction), beyond, index_[k]))
                    t1 = C(best.t);  // a box entered beyond it cannot hold a nearer root
            return false;
        });
        return best;
    }

    // closest() for each lane k in `lanes` of a bundle of rays, into hits[k]. The bundle goes down the tree
    // as one slab ray, nearest first, until no lane can find a nearer root; in a leaf the bundle, then each
    // lane's ray, is tried against each ellipsoid's box, then each lane's exactly (the lanes are set up where
    // the bundle first meets a box). Rays from different origins (a tile's mirrored rays) widen as they go,
    // and go as a bundle where their directions are narrow_directions() (off a floor or a large sphere), or
    // where the scene has no more ellipsoids than the bundle has rays, so that it tries each at most once for
    // them all; otherwise a wide bundle's descent costs more than it saves (docs/speed.md).
    template <int N>
    void closest(const V (&origins)[N], const V (&directions)[N], unsigned lanes, double min_t,
                 NearestHit<Real> (&hits)[N]) const {
        for (unsigned m = lanes; m != 0; m &= m - 1) hits[lowest_bit(m)] = {};
        // The bundle's edges: per axis from the least origin and direction to the greatest
        // (valid for t >= 0).
        SlabRay<C> ray;
        C o_lo[3], o_hi[3], d_lo[3], d_hi[3];
        bounds_of(origins, lanes, o_lo, o_hi);
        bounds_of(directions, lanes, d_lo, d_hi);
        const bool bundled = lanes != 0 && (lanes & (lanes - 1)) != 0 && !ellipsoids_.empty() &&
                             (narrow_directions(d_lo, d_hi, lanes) ||
                              ellipsoids_.size() <= static_cast<std::size_t>(bit_count(lanes))) &&
                             make_slab_ray(o_lo, o_hi, d_lo, d_hi, least_direction_, ray) &&
                             guarded(o_lo, o_hi);
        if (!bundled) {
            for (unsigned m = lanes; m != 0; m &= m - 1)
                hits[lowest_bit(m)] = closest(origins[lowest_bit(m)], directions[lowest_bit(m)], min_t);
            return;
        }
        const Real beyond = visible_beyond(Real(min_t));
        LaneRays<Real, N> rays;  // NOLINT(cppcoreguidelines-pro-type-member-init): set() before use
        bool rays_set = false;
        traverse<Visit::NearestFirst, true>(ray, std::numeric_limits<C>::infinity(), [&](Child leaf, C& t1) {
            for (std::uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
                const BuildBox<C> box = inflated_box<C>(ellipsoids_[i], gaps_);
                if (!meets_box(ray, box, t1)) continue;
                if (!rays_set)
                    rays.set(origins, directions, lanes, std::numeric_limits<C>::infinity()), rays_set = true;
                Real hit[N], near[N], far[N];
                for (unsigned m = rays.roots(ellipsoids_[i], box, lanes, hit, near, far); m != 0;
                     m &= m - 1) {
                    const int k = lowest_bit(m);
                    if (hits[k].offer(Roots<Real>{hit[k], near[k], far[k]}, beyond, index_[i]))
                        rays.t1[k] = C(hits[k].t);
                }
            }
            if (!rays_set) return false;
            C farthest = 0;  // no box entered beyond every lane's nearest root holds a nearer one
            for (unsigned m = lanes; m != 0; m &= m - 1)
                farthest = std::max(farthest, rays.t1[lowest_bit(m)]);
            t1 = farthest;
            return false;
        });
    }

    // Whether a ray from origin with a direction within [d_lo, d_hi] (per axis) may meet
    // some ellipsoid's box: where not, closest() finds nothing for any such ray, alone or
    // in a bundle (the bundle's own culling, for the whole range at once).
    bool may_meet(const V& origin, const C (&d_lo)[3], const C (&d_hi)[3]) const {
        const C o[3] = {C(origin.x), C(origin.y), C(origin.z)};
        SlabRay<C> ray;
        if (ellipsoids_.empty()) return false;
        if (!make_slab_ray(o, o, d_lo, d_hi, least_direction_, ray) || !guarded(o, o)) return true;
        bool met = false;
        traverse<Visit::AnyOrder, true>(ray, std::numeric_limits<C>::infinity(), [&](Child leaf, C& t1) {
            for (std::uint32_t i = leaf.first; i < leaf.first + leaf.count && !met; ++i)
                met = meets_box(ray, inflated_box<C>(ellipsoids_[i], gaps_), t1);
            return met;
        });
        return met;
    }

    // closest() with min_t kEyeRayMinT for each eye ray of a block (eye_block.h). The block descends the
    // tree as one slab ray from the camera, nearest first, and tries each ellipsoid whose box it may meet,
    // until no box ahead can hold a root nearer than every pixel's; where the camera is beyond some guard,
    // ray by ray.
    template <int Rows, int Columns>
    void closest(EyeBlock<Real, Rows, Columns>& block) const;  // bvh_traverse.h

    // As BruteForce::occluded(): whether some ellipsoid blocks the shadow ray, trying first the hint
    // `blocker` (a position in leaf order, any value: blocker_hints.h), which becomes the one found. The
    // ellipsoids in cleared (bit 0) are not tried: the caller knows that they cannot block. Past the hint,
    // each one's box is tried first by the descent's slab ray where boxes may cull it (measured in
    // docs/speed.md).
    bool occluded(const V& point, const V& to_light, std::uint32_t& blocker,
                  const ClearedLanes& cleared = {}) const {
        const ClearedLanes skip = cleared_in_leaf_order(cleared);
        if (blocker < ellipsoids_.size() && (skip.of(blocker) & 1U) == 0 &&
            blocks_segment(ellipsoids_[blocker], point, to_light))
            return true;
        const OneRay ray = one_ray(point, to_light);
        const std::uint32_t tried = blocker;
        bool blocked = false;
        traverse<Visit::AnyOrder>(ray, C(1), [&](Child leaf, C&) {
            for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count && !blocked; ++k)
                if (k != tried && (skip.of(k) & 1U) == 0 &&
                    (!ray.culls() || meets_box(ray.slab, inflated_box<C>(ellipsoids_[k], gaps_), C(1))) &&
                    blocks_segment(ellipsoids_[k], point, to_light))
                    blocker = k, blocked = true;
            return blocked;
        });
        return blocked;
    }

    // occluded() for each lane k in `lanes` (bit k) of a bundle of shadow rays from points[k] to the light
    // at `light` (to_light = light - points[k], as the shading computes it): the lanes that some ellipsoid
    // blocks. The bundle goes down the tree as one slab ray and its lanes are tried one by one in the leaves
    // it reaches: one descent instead of one a ray, where the points lie close (a tile's points on one
    // ellipsoid). The ellipsoids in cleared are not tried for their lanes. The bundle's edges converge on
    // the light (shadow_bundle_edges(), slab_rays.h).
    template <int N>
    unsigned occluded(const V (&points)[N], const V& light, unsigned lanes, std::uint32_t& blocker,
                      const ClearedLanes& cleared = {}) const {
        if (lanes == 0 || (lanes & (lanes - 1)) == 0) {  // one ray
            const int k = lanes == 0 ? 0 : lowest_bit(lanes);
            return lanes != 0 && occluded(points[k], light - points[k], blocker, cleared.lane(k)) ? lanes
                                                                                                  : 0U;
        }
        V to_light[N];
        for (unsigned m = lanes; m != 0; m &= m - 1) to_light[lowest_bit(m)] = light - points[lowest_bit(m)];
        C o_lo[3], o_hi[3], d_lo[3], d_hi[3];
        shadow_bundle_edges(points, light, lanes, o_lo, o_hi, d_lo, d_hi);
        unsigned blocked = 0;
        SlabRay<C> ray;
        if (ellipsoids_.empty() || !make_slab_ray(o_lo, o_hi, d_lo, d_hi, least_direction_, ray) ||
            !guarded(o_lo, o_hi)) {
            for (unsigned m = lanes; m != 0; m &= m - 1)  // beyond the fast case: ray by ray
                if (occluded(points[lowest_bit(m)], to_light[lowest_bit(m)], blocker,
                             cleared.lane(lowest_bit(m))))
                    blocked |= 1U << lowest_bit(m);
            return blocked;
        }
        // An ellipsoid's box is tried against the bundle, then against each lane's own ray, whose set-up
        // waits for the first box the bundle meets (the heavy scene through the tree 332 -> 306 ms); the
        // lanes met go to blocked_lanes() (shadow_prefilter.h). The hint for all lanes at once first.
        LaneRays<Real, N> rays;  // NOLINT(cppcoreguidelines-pro-type-member-init): set() before use
        bool rays_set = false;
        const std::uint32_t tried = blocker;
        const ClearedLanes skip = cleared_in_leaf_order(cleared);
        auto try_ellipsoid = [&](std::uint32_t i, unsigned open) {
            open &= ~skip.of(i);
            const BuildBox<C> box = inflated_box<C>(ellipsoids_[i], gaps_);
            if (open == 0 || !meets_box(ray, box, C(1))) return;
            if (!rays_set) rays.set(points, to_light, lanes, 1), rays_set = true;
            const unsigned met = open & rays.meeting(box);
            if (met == 0) return;
            const auto yes = static_cast<unsigned>(blocked_lanes<N>(ellipsoids_[i], rays.from[0],
                                                                    rays.from[1], rays.from[2], rays.along[0],
                                                                    rays.along[1], rays.along[2], met));
            if (yes != 0) blocked |= yes, blocker = i;
        };
        if (tried < ellipsoids_.size()) try_ellipsoid(tried, lanes);
        unsigned open = lanes & ~blocked;
        if (open == 0) return blocked;
        traverse<Visit::AnyOrder, true>(ray, C(1), [&](Child leaf, C&) {
            for (std::uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
                if (i == tried) continue;
                try_ellipsoid(i, open);
                open &= ~blocked;
                if (open == 0) return true;
            }
            return false;
        });
        return blocked;
    }

    // Calls f(i) for each ellipsoid i of the scene in the leaves whose boxes hold point:
    // at least every ellipsoid whose own box does (those that may hold it: light_shells.h).
    template <typename F>
    void boxes_holding(const V& point, F f) const;  // bvh_traverse.h

    // Ellipsoid i of the scene.
    const Ellipsoid<Real>& ellipsoid(std::uint32_t i) const { return ellipsoids_[position_[i]]; }

    std::size_t node_count() const { return nodes_.size(); }

private:
    using Child = WideChild;
    using Node = WideNode<C, Width>;
    struct StackEntry {
        Child child;
        C near;  // where the ray enters its box
    };
    bool guarded(const C (&o_lo)[3], const C (&o_hi)[3]) const {
        return within_guard(bounds_, guard_, o_lo, o_hi);
    }

    ClearedLanes cleared_in_leaf_order(const ClearedLanes& cleared) const {
        return cleared.renumbered(position_);
    }
    // The binary tree's depth is below 32 + log2(N) (bvh_build.h), under 64 as the items
    // are counted in 32 bits, so that of the wide tree too (96 leaves a margin), and each
    // level leaves at most Width - 1 entries on the stack.
    static constexpr int kStack = 96 * (Width - 1) + 1;

    // One ray as the descent takes it: its slab ray, unless a direction component has no finite inverse
    // (then every ellipsoid is visited), and whether its origin is within every guard distance.
    struct OneRay {
        SlabRay<C> slab;
        bool sloped, guarded;
        bool culls() const { return sloped && guarded; }  // boxes may cull it
    };
    OneRay one_ray(const V& origin, const V& direction) const {
        const C o[3] = {C(origin.x), C(origin.y), C(origin.z)};
        const C d[3] = {C(direction.x), C(direction.y), C(direction.z)};
        OneRay ray{};
        ray.sloped = make_slab_ray(o, o, d, d, least_direction_, ray.slab);
        ray.guarded = guarded(o, o);
        return ray;
    }
    // The order of a descent's children: the closest-hit queries want the nearest first,
    // the any-hit queries take any (any blocker will do).
    enum class Visit { NearestFirst, AnyOrder };
    // Visits the leaves whose boxes the ray may meet within [0, t1] in kVisit's order;
    // leaf(child, t1) may lower t1 and returns true to end the search. A slab ray is
    // kGuarded where its origin lies within every ellipsoid's guard (guarded()).
    template <Visit kVisit, typename Leaf>
    void traverse(const OneRay& ray, C t1, Leaf leaf) const;
    template <Visit kVisit, bool kGuarded, typename Leaf>
    void traverse(const SlabRay<C>& ray, C t1, Leaf leaf) const;

    LargeVector<Node> nodes_;
    Child root_{0, 0};
    BuildBox<C> bounds_{};                     // of every box
    C guard_ = 0;                              // the smallest guard
    C least_direction_ = 0;                    // make_slab_ray()'s least
    BoxGaps<Real> gaps_;                       // how far each box is grown
    LargeVector<Ellipsoid<Real>> ellipsoids_;  // in leaf order
    LargeVector<std::uint32_t> index_;         // ellipsoids_[k] is the ellipsoid index_[k] of the scene
    LargeVector<std::uint32_t> position_;      // and ellipsoid i is ellipsoids_[position_[i]]
};

template <typename Real, int Width>
template <typename EllipsoidOf>
Bvh<Real, Width>::Bvh(std::size_t count, EllipsoidOf ellipsoid_of, unsigned threads) {
    // Large trees are prepared on two threads: the items, the ellipsoids in leaf order.
    const bool two_threads = threads > 1 && count >= BinaryTreeBuilder<C>::kItemsPerThread;
    auto both = [two_threads](auto other, auto here) {
        if (two_threads)
            run_beside(other, here);
        else
            other(), here();
    };
    // The items, halves on two threads (their fresh pages' first touch is most of it:
    // random 10k read and prepared 9.0 -> 8.0 ms), and the scene's extent, for the gaps
    // of the boxes: where some ellipsoid is thin beside it, the items are made again.
    LargeVector<BuildItem<C>> items(count);
    SceneExtent<C> halves[2];
    auto make_items = [&](std::size_t first, std::size_t last, SceneExtent<C>& extent) {
        for (std::size_t i = first; i < last; ++i) {
            const Ellipsoid<Real> e = ellipsoid_of(i);
            items[i] = build_item<C>(e, static_cast<std::uint32_t>(i), gaps_);
            extent.add(e);
        }
    };
    auto make_all = [&] {
        both([&] { make_items(count / 2, count, halves[1]); }, [&] { make_items(0, count / 2, halves[0]); });
    };
    make_all();
    SceneExtent<C> scene = halves[0];
    scene.add(halves[1]);
    gaps_ = BoxGaps<Real>(scene.extent());
    if (scene.smallest < gaps_.grown_below()) make_all();
    const LargeVector<BuildNode<C>> binary = BinaryTreeBuilder<C>().build(items, threads);
    index_.resize(count), position_.resize(count);
    for (std::uint32_t k = 0; k < items.size(); ++k)
        index_[k] = items[k].index, position_[items[k].index] = k;
    LargeVector<BuildItem<C>>().swap(items);  // not needed past this: a lower peak
    if (binary.empty()) return;
    bounds_ = binary[0].box, guard_ = binary[0].guard;
    // The ellipsoids in leaf order beside the collapse.
    auto order_ellipsoids = [&] {
        ellipsoids_.reserve(count);
        C largest = 0;  // scale
        for (const std::uint32_t i : index_) {
            ellipsoids_.push_back(ellipsoid_of(i));
            C s[3];
            abs_scales(ellipsoids_.back(), s);
            largest = std::max({largest, s[0], s[1], s[2]});
        }
        // Below it in every component, d / s may be below Real's normal range (twice: a margin).
        least_direction_ = 2 * C(std::numeric_limits<Real>::min()) * largest;
    };
    auto collapse_tree = [&] { root_ = collapse<Width>(binary, nodes_); };
    both(order_ellipsoids, collapse_tree);
}

}  // namespace rt

#include "raytracer/accel/bvh_traverse.h"  // Bvh::traverse(), the descent
