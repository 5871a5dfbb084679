// An ellipsoid's box as the tree builds it (bvh.h): grown by the gap that keeps every
// culled test one that would find no usable root (exact_culling.h), the reach from which
// that gap holds (its guard), and the margin a box needs past it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "raytracer/accel/bvh_build.h"
#include "raytracer/accel/exact_culling.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"

namespace rt {

// |scale| of an ellipsoid on each axis, and the least of the three.
template <typename C, typename Real>
void abs_scales(const Ellipsoid<Real>& e, C (&s)[3]) {
    using std::abs;
    s[0] = abs(C(e.scale.x)), s[1] = abs(C(e.scale.y)), s[2] = abs(C(e.scale.z));
}
template <typename C>
C smallest_of(const C (&s)[3]) {
    return std::min({s[0], s[1], s[2]});
}

// How far the tree grows an ellipsoid's box, and from how far the box may cull a ray
// (exact_culling.h): grown by kCullingGap of each scale, it culls rays from within
// 2e10 smallest scales (double), which covers nearly every scene. An ellipsoid thin or
// small beside its scene (a disc 1e-11 thick seen from 30 away: |o'| = 3e12) is grown
// by the larger gap that culling from anywhere in the scene needs, up to
// kLargestCullingGap; past that, a ray from beyond its reach meets its box grown for
// the ray's distance (margin_per_reach(), children_met()). (Only
// ellipsoids below 1e-13 of the scene's extent take the largest gap, under a thousand
// ulps of its coordinates: in a scene with one ellipsoid some 1e13 times larger than all
// the others, every other box is doubled.)
template <typename Real>
class BoxGaps {
public:
    using C = AtLeastDouble<Real>;

    BoxGaps() = default;  // kCullingGap for every ellipsoid
    // For a scene whose rays start within `extent` (max-norm) of every point of every box.
    explicit BoxGaps(C extent) {
        const C needed = 2 * C(gap_per_reach<Real>()) * extent;  // gap times scale: guard = extent
        if (!(needed / C(kCullingGap) <= std::numeric_limits<C>::max())) return;
        needed_ = needed, grown_below_ = needed / C(kCullingGap);
    }

    // The gap of an ellipsoid whose smallest scale is `smallest`, in its unit sphere's space.
    C gap(C smallest) const {
        return smallest >= grown_below_ ? C(kCullingGap)
                                        : std::min(C(kLargestCullingGap), needed_ / smallest);
    }
    // The max-norm distance from which its box may cull a ray: the reach that gap holds,
    // halved, as the Euclidean distance is at most sqrt(3) times the max-norm one. 0 for
    // a scale that is not a number.
    C guard(C smallest) const {
        const C guard = gap(smallest) / C(gap_per_reach<Real>()) * smallest / 2;
        return guard <= std::numeric_limits<C>::max() ? guard : guard > 0 ? std::numeric_limits<C>::max() : 0;
    }
    // The smallest scales below which gap() may exceed kCullingGap.
    C grown_below() const { return grown_below_; }

private:
    C needed_ = 0;       // the gap times the smallest scale that culling from anywhere needs
    C grown_below_ = 0;  // needed_ / kCullingGap
};

// What BoxGaps is made from, gathered ellipsoid by ellipsoid: rays start at the eye (the
// origin) or on an ellipsoid, inside its box (within c +- (1 + kLargestCullingGap) s),
// so within twice the largest |c| + (1 + kLargestCullingGap) |s| (max-norm) of every
// box; and the smallest scale of all. A ray that starts elsewhere (a hit point's own
// rounding) is still exact: each ray's origin is checked against the guards.
template <typename C>
struct SceneExtent {
    C farthest = 0, smallest = std::numeric_limits<C>::infinity();

    template <typename Real>
    void add(const Ellipsoid<Real>& e) {
        C s[3];
        abs_scales(e, s);
        const C c[3] = {C(e.centre.x), C(e.centre.y), C(e.centre.z)};
        for (int a = 0; a < 3; ++a)
            farthest = std::max(farthest, std::abs(c[a]) + (1 + C(kLargestCullingGap)) * s[a]);
        smallest = std::min(smallest, smallest_of(s));
    }
    void add(const SceneExtent& other) {
        farthest = std::max(farthest, other.farthest), smallest = std::min(smallest, other.smallest);
    }
    C extent() const { return 2 * farthest; }  // from any such point to any other
};

// An ellipsoid's box: grown by its gap of each scale (BoxGaps), by 4 ulps of the centre
// too, so that the box's own rounding stays inside the gap even for a small ellipsoid
// far from the origin, and by the smallest subnormal, as a scale below 500 of them is
// its own product with 1 + kCullingGap: a gap of one ulp is still > kCullingGap of it.
// Computed where a leaf is visited, not stored: 48 bytes more an ellipsoid, and no
// faster measured (docs/speed.md, "Tried and dropped").
template <typename C, typename Real>
BuildBox<C> inflated_box(const Ellipsoid<Real>& e, const BoxGaps<Real>& gaps) {
    using std::abs;
    const C c[3] = {C(e.centre.x), C(e.centre.y), C(e.centre.z)};
    C s[3];
    abs_scales(e, s);
    const C grow = 1 + gaps.gap(smallest_of(s));
    BuildBox<C> box;
    for (int a = 0; a < 3; ++a) {
        const C half = s[a] * grow + abs(c[a]) * 4 * std::numeric_limits<C>::epsilon() +
                       std::numeric_limits<C>::denorm_min();
        box.lo[a] = c[a] - half, box.hi[a] = c[a] + half;
    }
    return box;
}

// Ellipsoid e as the tree's build takes it (bvh_build.h): its inflated box, its centre
// and its guard distance (BoxGaps).
template <typename C, typename Real>
BuildItem<C> build_item(const Ellipsoid<Real>& e, std::uint32_t index, const BoxGaps<Real>& gaps) {
    C s[3];
    abs_scales(e, s);
    BuildItem<C> item;
    item.box = inflated_box<C>(e, gaps);
    item.centre[0] = C(e.centre.x), item.centre[1] = C(e.centre.y), item.centre[2] = C(e.centre.z);
    item.guard = gaps.guard(smallest_of(s));
    // inf where the aspect is not a finite number (a scale of 0 or NaN): such a box is
    // never culled past its guard (0 for NaN).
    const C rate = C(margin_per_reach<Real>()) * (std::max({s[0], s[1], s[2]}) / smallest_of(s));
    item.rate = rate <= std::numeric_limits<C>::max() ? rate : std::numeric_limits<C>::infinity();
    item.index = index;
    return item;
}

}  // namespace rt
