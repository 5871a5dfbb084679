// The acceleration layer: a bounding volume hierarchy over the ellipsoids' boxes, with
// the queries of brute_force.h (closest hit, any hit) in time that grows like log N.
//
// Layout and traversal follow pbrt-v4's BVHAggregate (M. Pharr, W. Jakob, G. Humphreys,
// Physically Based Rendering, 4th ed., section 7.3): nodes in depth-first order, the
// first child next to its parent, the nearer child visited first; the tree is built
// top-down with binned surface-area-heuristic splits (I. Wald, "On fast Construction of
// SAH-based Bounding Volume Hierarchies", IEEE Symposium on Interactive Ray Tracing 2007),
// O(N log N).
//
// Exactness: a query returns what brute_force.h returns, bit for bit. Each ellipsoid's
// box is its axis-aligned bounding box grown by kInflation of each scale, a gap of
// 1e-3 in the unit sphere's space; a root that intersect() reports lies within a few
// ulps of |o'| of the unit sphere (the rounding of the mapped origin, plus the tangency
// allowance, ellipsoid.h), so its point lies deep inside the box, and the slab test's
// own rounding (a few ulps of the box's distance) cannot move it out. Both hold only
// while the ray's origin is within kReach of the ellipsoid's smallest scale (|o'| <=
// 1e6 in double: rounding ~1e-10 against the gap of 1e-3), as in sphere_bounds.h. So a
// box is culled only for a ray from within the guard distance of every ellipsoid under
// it (Node::guard); beyond that its children are visited unculled, and the ellipsoids of
// a leaf are always tried with the exact intersect(). Ties between equal roots go to
// the lower index (NearestHit::replaced_by()), as in the loop over all.
//
// Memory: the tree and a copy of the ellipsoids in leaf order; a query uses a fixed
// stack of kMaxDepth entries, the same for any scene.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
class Bvh {
public:
    using V = Vec3<Real>;
    using C = AtLeastDouble<Real>;  // boxes and slab tests

    explicit Bvh(const std::vector<Ellipsoid<Real>>& ellipsoids);

    // As BruteForce::closest(): the nearest visible root beyond min_t.
    NearestHit<Real> closest(const V& origin, const V& direction, double min_t) const {
        const Real beyond = visible_beyond<Real>(min_t);
        NearestHit<Real> best;
        traverse(origin, direction, C(min_t), std::numeric_limits<C>::infinity(),
                 [&](std::uint32_t node, C& t1) {
                     const Node& leaf = nodes_[node];
                     for (std::uint32_t k = leaf.offset; k < leaf.offset + leaf.count; ++k) {
                         Real t;
                         bool inside;
                         if (visible_root(intersect(items_[k], origin, direction), beyond, t, inside) &&
                             best.replaced_by(t, index_[k])) {
                             best = {index_[k], t, inside};
                             t1 = C(t);  // a farther box cannot hold a nearer root
                         }
                     }
                     return false;
                 });
        return best;
    }

    // As BruteForce::occluded(): whether some ellipsoid blocks the shadow ray.
    bool occluded(const V& point, const V& to_light) const {
        bool blocked = false;
        traverse(point, to_light, C(spec::kShadowRayMinT), C(1), [&](std::uint32_t node, C&) {
            const Node& leaf = nodes_[node];
            for (std::uint32_t k = leaf.offset; k < leaf.offset + leaf.count; ++k)
                if (blocks_shadow_ray(intersect(items_[k], point, to_light))) return blocked = true;
            return false;
        });
        return blocked;
    }

    std::size_t node_count() const { return nodes_.size(); }

    static constexpr double kInflation = 1e-3;  // as sphere_bounds.h
    static constexpr int kMaxDepth = 64;        // the builder splits at the median below kMedianDepth
    static constexpr int kMedianDepth = 32;     // 32 + log2(1e9) < 64

private:
    struct Box {
        C lo[3], hi[3];
    };
    struct Node {
        Box box;
        C guard;                   // rays from within this max-norm distance of every corner may cull
        std::uint32_t offset = 0;  // a leaf's first item; an inner node's second child
        std::uint16_t count = 0;   // a leaf's items (> 0); 0 for an inner node
        std::uint16_t axis = 0;    // an inner node's split axis
    };
    struct Item {
        Box box;
        C centre[3];
        C guard;
        std::uint32_t index;
    };

    static constexpr std::size_t kLeafItems = 8;  // at most, where the SAH prefers a leaf
    static constexpr int kBins = 16;
    // The SAH's costs: a box test, and a ray/ellipsoid test (divisions and a square root).
    static constexpr double kBoxCost = 1, kEllipsoidCost = 2;

    // Visits the leaves whose boxes the ray may meet within [t0, t1]; leaf(node, t1)
    // may lower t1 and returns true to end the search.
    template <typename Leaf>
    void traverse(const V& origin, const V& direction, C t0, C t1, Leaf leaf) const;

    // Whether the ray meets box b within [t0, t1]. A slab is computed with at most 3
    // roundings, so the far end is widened by 2 gamma(3) (pbrt-v4 section 6.8.2); a NaN
    // (a ray parallel to a slab, starting on its face) leaves the interval as it is.
    static bool meets(const Box& b, const C (&o)[3], const C (&inv)[3], C t0, C t1) {
        constexpr C kGamma3 =
            3 * std::numeric_limits<C>::epsilon() / 2 / (1 - 3 * std::numeric_limits<C>::epsilon() / 2);
        for (int a = 0; a < 3; ++a) {
            C near = (b.lo[a] - o[a]) * inv[a], far = (b.hi[a] - o[a]) * inv[a];
            if (near > far) std::swap(near, far);
            far *= 1 + 2 * kGamma3;
            if (near > t0) t0 = near;
            if (far < t1) t1 = far;
        }
        return t0 <= t1;
    }

    // The largest max-norm distance from o to a point of b.
    static C farthest(const Box& b, const C (&o)[3]) {
        using std::abs;
        C d = 0;
        for (int a = 0; a < 3; ++a) d = std::max({d, abs(b.lo[a] - o[a]), abs(b.hi[a] - o[a])});
        return d;
    }

    std::uint32_t build(std::vector<Item>& items, std::size_t first, std::size_t last, int depth);
    std::size_t split(std::vector<Item>& items, std::size_t first, std::size_t last, const Box& box,
                      int depth, int& axis) const;
    static C area(const Box& b) {
        const C x = b.hi[0] - b.lo[0], y = b.hi[1] - b.lo[1], z = b.hi[2] - b.lo[2];
        return x * y + y * z + z * x;  // half the surface area
    }

    std::vector<Node> nodes_;
    std::vector<Ellipsoid<Real>> items_;  // in leaf order
    std::vector<std::uint32_t> index_;    // items_[k] is the ellipsoid index_[k] of the scene
};

template <typename Real>
template <typename Leaf>
void Bvh<Real>::traverse(const V& origin, const V& direction, C t0, C t1, Leaf leaf) const {
    if (nodes_.empty()) return;
    const C o[3] = {C(origin.x), C(origin.y), C(origin.z)};
    const C d[3] = {C(direction.x), C(direction.y), C(direction.z)};
    const C inv[3] = {1 / d[0], 1 / d[1], 1 / d[2]};
    // The nodes still to visit; the top bit marks a node whose box may cull (guarded).
    constexpr std::uint32_t kGuarded = 0x80000000U;
    std::array<std::uint32_t, kMaxDepth + 1> stack;
    int size = 0;
    stack[size++] = 0;
    while (size > 0) {
        const std::uint32_t entry = stack[--size];
        const std::uint32_t index = entry & ~kGuarded;
        const Node& node = nodes_[index];
        bool guarded = (entry & kGuarded) != 0;
        if (!guarded) guarded = farthest(node.box, o) <= node.guard;  // NaN: not guarded
        if (guarded && !meets(node.box, o, inv, t0, t1)) continue;
        if (node.count > 0) {
            if (leaf(index, t1)) return;
            continue;
        }
        const std::uint32_t flag = guarded ? kGuarded : 0;
        std::uint32_t near = index + 1, far = node.offset;
        if (d[node.axis] < 0) std::swap(near, far);
        stack[size++] = far | flag;
        stack[size++] = near | flag;
    }
}

template <typename Real>
Bvh<Real>::Bvh(const std::vector<Ellipsoid<Real>>& ellipsoids) {
    if (ellipsoids.empty()) return;
    // Rounding of intersect() in the unit space grows like epsilon(Real) times the
    // distance in units of the smallest scale: as sphere_bounds.h, at most 1e6 smallest
    // scales in double (1e2 in float). The Euclidean distance is at most sqrt(3) times
    // the max-norm one that the traversal measures: the guard is half the reach.
    const C reach = std::numeric_limits<Real>::digits > 30 ? C(1e6) : C(1e2);
    std::vector<Item> items(ellipsoids.size());
    for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
        using std::abs;
        const Ellipsoid<Real>& e = ellipsoids[i];
        const C c[3] = {C(e.centre.x), C(e.centre.y), C(e.centre.z)};
        const C s[3] = {abs(C(e.scale.x)), abs(C(e.scale.y)), abs(C(e.scale.z))};
        Item& item = items[i];
        for (int a = 0; a < 3; ++a) {
            // Grown by 4 ulps of the centre too, so that the box's own rounding stays
            // inside the gap even for a small ellipsoid far from the origin.
            const C half = s[a] * (1 + C(kInflation)) + abs(c[a]) * 4 * std::numeric_limits<C>::epsilon();
            item.box.lo[a] = c[a] - half, item.box.hi[a] = c[a] + half;
            item.centre[a] = c[a];
        }
        const C guard = std::min({s[0], s[1], s[2]}) * reach / 2;
        item.guard = guard <= std::numeric_limits<C>::max() ? guard : std::numeric_limits<C>::max();
        item.index = static_cast<std::uint32_t>(i);
    }
    nodes_.reserve(2 * items.size());
    build(items, 0, items.size(), 0);
    items_.reserve(items.size()), index_.reserve(items.size());
    for (const Item& item : items) items_.push_back(ellipsoids[item.index]), index_.push_back(item.index);
}

template <typename Real>
std::uint32_t Bvh<Real>::build(std::vector<Item>& items, std::size_t first, std::size_t last, int depth) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.box = items[first].box, node.guard = items[first].guard;
    for (std::size_t k = first + 1; k < last; ++k) {
        for (int a = 0; a < 3; ++a) {
            node.box.lo[a] = std::min(node.box.lo[a], items[k].box.lo[a]);
            node.box.hi[a] = std::max(node.box.hi[a], items[k].box.hi[a]);
        }
        node.guard = std::min(node.guard, items[k].guard);
    }
    int axis = 0;
    const std::size_t middle = last - first <= 1 ? last : split(items, first, last, node.box, depth, axis);
    if (middle == last) {
        node.offset = static_cast<std::uint32_t>(first);
        node.count = static_cast<std::uint16_t>(last - first);
    } else {
        build(items, first, middle, depth + 1);
        node.offset = build(items, middle, last, depth + 1);
        node.axis = static_cast<std::uint16_t>(axis);  // the first child lies lower along it
    }
    nodes_[index] = node;
    return index;
}

// Where to split items [first, last) (the first part lies lower along axis), or last
// for a leaf: the binned SAH's best split over the three axes; at the median of the
// widest axis of the centres where it finds none but the items are too many for a leaf,
// and at depth kMedianDepth and below, which bounds the depth.
template <typename Real>
std::size_t Bvh<Real>::split(std::vector<Item>& items, std::size_t first, std::size_t last, const Box& box,
                             int depth, int& axis) const {
    const std::size_t n = last - first;
    C lo[3], hi[3];  // of the centres
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = items[first].centre[a];
    for (std::size_t k = first + 1; k < last; ++k)
        for (int a = 0; a < 3; ++a)
            lo[a] = std::min(lo[a], items[k].centre[a]), hi[a] = std::max(hi[a], items[k].centre[a]);
    int widest = 0;
    for (int a = 1; a < 3; ++a)
        if (hi[a] - lo[a] > hi[widest] - lo[widest]) widest = a;
    auto median = [&](int a) {
        const std::size_t middle = first + n / 2;
        std::nth_element(items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(middle),
                         items.begin() + std::ptrdiff_t(last),
                         [a](const Item& x, const Item& y) { return x.centre[a] < y.centre[a]; });
        axis = a;
        return middle;
    };
    if (depth >= kMedianDepth) return median(widest);
    // The bin of a centre along axis a; NaN and overflow go to the end bins.
    auto bin_of = [&](const Item& item, int a, C scale) {
        const C x = (item.centre[a] - lo[a]) * scale;
        return x >= C(kBins - 1) ? kBins - 1 : x > 0 ? static_cast<int>(x) : 0;
    };
    C best_cost = C(kEllipsoidCost) * C(n);  // a leaf
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a) {
        if (!(hi[a] > lo[a])) continue;
        const C scale = C(kBins) / (hi[a] - lo[a]);
        Box bins[kBins];
        std::size_t counts[kBins] = {};
        for (std::size_t k = first; k < last; ++k) {
            const int b = bin_of(items[k], a, scale);
            if (counts[b]++ == 0) bins[b] = items[k].box;
            for (int j = 0; j < 3; ++j)
                bins[b].lo[j] = std::min(bins[b].lo[j], items[k].box.lo[j]),
                bins[b].hi[j] = std::max(bins[b].hi[j], items[k].box.hi[j]);
        }
        // Sweep from the right: the area and count of bins [b, kBins) for each b.
        C right_area[kBins];
        std::size_t right_count[kBins];
        Box grown{};
        std::size_t count = 0;
        for (int b = kBins - 1; b > 0; --b) {
            if (counts[b] > 0) {
                if (count == 0) grown = bins[b];
                for (int j = 0; j < 3; ++j)
                    grown.lo[j] = std::min(grown.lo[j], bins[b].lo[j]),
                    grown.hi[j] = std::max(grown.hi[j], bins[b].hi[j]);
                count += counts[b];
            }
            right_area[b] = count > 0 ? area(grown) : 0, right_count[b] = count;
        }
        count = 0;
        for (int b = 0; b + 1 < kBins; ++b) {
            if (counts[b] > 0) {
                if (count == 0) grown = bins[b];
                for (int j = 0; j < 3; ++j)
                    grown.lo[j] = std::min(grown.lo[j], bins[b].lo[j]),
                    grown.hi[j] = std::max(grown.hi[j], bins[b].hi[j]);
                count += counts[b];
            }
            if (count == 0 || right_count[b + 1] == 0) continue;
            const C cost =
                C(kBoxCost) + C(kEllipsoidCost) *
                                  (C(count) * area(grown) + C(right_count[b + 1]) * right_area[b + 1]) /
                                  area(box);
            if (cost < best_cost) best_cost = cost, best_axis = a, best_bin = b + 1;
        }
    }
    if (best_axis < 0) return n <= kLeafItems ? last : median(widest);
    const C scale = C(kBins) / (hi[best_axis] - lo[best_axis]);
    const auto middle =
        std::partition(items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(last),
                       [&](const Item& item) { return bin_of(item, best_axis, scale) < best_bin; });
    const auto m = static_cast<std::size_t>(middle - items.begin());
    if (m == first || m == last) return median(best_axis);
    axis = best_axis;
    return m;
}

}  // namespace rt
