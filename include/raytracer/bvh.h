// The acceleration layer: a bounding volume hierarchy over the ellipsoids' boxes, with
// the queries of brute_force.h (closest hit, any hit) in time that grows like log N.
//
// The tree is built binary (bvh_build.h) and collapsed into nodes of Width children,
// whose boxes are stored as structure of arrays and tested against a ray in one loop
// over the lanes that the compiler turns into vector instructions (8 doubles, one
// AVX-512 register or two AVX2 ones, measured faster here than 4): Embree's BVH4/BVH8 (I. Wald et al.,
// "Embree: A Kernel Framework for Efficient CPU Ray Tracing", ACM TOG 33(4), 2014). Children are visited
// nearest first; the closest-hit query skips a subtree that starts beyond the nearest root found so far.
//
// Exactness: a query returns what brute_force.h returns, bit for bit. Each ellipsoid's
// box is its axis-aligned bounding box grown by kInflation of each scale, a gap of
// 1e-3 in the unit sphere's space; a root that intersect() reports lies within a few
// ulps of |o'| of the unit sphere (the rounding of the mapped origin, plus the tangency
// allowance, ellipsoid.h), so its point lies deep inside the box, and the slab test's
// own rounding (a few ulps of the box's distance) cannot move it out. A ray that runs
// in a slab's plane, where the slab test's 0 * inf is NaN, cannot reach a box's inside
// at all. Both hold only while the ray's origin is within kReach of the ellipsoid's
// smallest scale (|o'| <= 1e6 in double: rounding ~1e-10 against the gap of 1e-3), as
// in sphere_bounds.h: a child is culled only for a ray from within the guard distance
// of every ellipsoid under it, else visited unculled. A child whose box holds the
// ray's origin is never culled either: from a point on the surface (|o'| = 1 within
// rounding) along its tangent plane, o'.d' is a rounding residue, and where intersect()
// clamps the discriminant to zero (the tangency allowance) its second root c/q is
// c / |o'.d'|, anywhere along the ray, far outside the box (a shadow ray towards a
// light 2000 radii away leaves the box before t = 0.001 and is still "blocked" at
// t ~ 0.5). From outside the box, |o'.d'| / |d'| >= sqrt(1.001^2 - 1) ~ 0.045 bounds
// that root's distance from the tangent point to ~90 eps (1 + |o'|), deep inside the
// gap. The ellipsoids of a leaf are always tried with the exact intersect(). Ties
// between equal roots go to the lower index (NearestHit::replaced_by()), as in the loop
// over all.
//
// Memory: the tree and a copy of the ellipsoids in leaf order; a query uses a fixed
// stack, the same for any scene.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "raytracer/bit_scan.h"
#include "raytracer/bvh_build.h"
#include "raytracer/compiler.h"
#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real, int Width = 8>
class Bvh {
public:
    using V = Vec3<Real>;
    using C = AtLeastDouble<Real>;  // boxes and slab tests
    static_assert(Width >= 2 && Width <= 16, "a node holds 2 to 16 children");

    static constexpr double kInflation = 1e-3;  // as sphere_bounds.h

    // threads: how many may build the tree (1 or 2 are used).
    explicit Bvh(std::vector<Ellipsoid<Real>> ellipsoids, unsigned threads = 1);

    // As BruteForce::closest(): the nearest visible root beyond min_t.
    NearestHit<Real> closest(const V& origin, const V& direction, double min_t) const {
        const Real beyond = visible_beyond(Real(min_t));
        NearestHit<Real> best;
        traverse<true>(origin, direction, std::numeric_limits<C>::infinity(), [&](Child leaf, C& t1) {
            for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
                Real t;
                bool inside;
                if (visible_root(intersect(items_[k], origin, direction), beyond, t, inside) &&
                    best.replaced_by(t, index_[k])) {
                    best = {index_[k], t, inside};
                    t1 = C(t);  // a box entered beyond it cannot hold a nearer root
                }
            }
            return false;
        });
        return best;
    }

    // As BruteForce::occluded(): whether some ellipsoid blocks the shadow ray, trying
    // first the one that blocked this light last (blocker: a position in leaf order).
    bool occluded(const V& point, const V& to_light, std::uint32_t& blocker) const {
        if (blocker < items_.size() && blocks_segment(items_[blocker], point, to_light)) return true;
        bool blocked = false;
        traverse<false>(point, to_light, C(1), [&](Child leaf, C&) {
            for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k)
                if (k != blocker && blocks_segment(items_[k], point, to_light)) {
                    blocker = k;
                    return blocked = true;
                }
            return false;
        });
        return blocked;
    }

    // Ellipsoid i of the scene.
    const Ellipsoid<Real>& ellipsoid(std::uint32_t i) const { return items_[position_[i]]; }

    std::size_t node_count() const { return nodes_.size(); }

private:
    // A child: the wide node `first` when count is 0, else the leaf of items
    // [first, first + count).
    struct Child {  // trivial: the traversal's stack is not initialised
        std::uint32_t first, count;
    };
    // Width children; their boxes (side 0 the low corner, 1 the high one), by axis and
    // lane, and guards: a child may be culled for a ray whose origin lies within this
    // max-norm distance of each of its corners.
    struct Node {
        C box[2][3][Width];
        C guard[Width];
        Child child[Width];
        unsigned used;  // bit k for each child k in use
    };
    struct StackEntry {
        Child child;
        C near;  // where the ray enters its box
    };
    // A ray as the slab tests take it: its origin and the inverse of its direction.
    struct SlabRay {
        C o[3], inv[3];
    };
    // The binary tree's depth is below 32 + log2(N) (bvh_build.h), so that of the
    // wide tree too, and each level leaves at most Width - 1 entries on the stack.
    static constexpr int kStack = 96 * (Width - 1) + 1;

    // Visits the leaves whose boxes the ray may meet within [0, t1], nearest first
    // where kNearestFirst (else in any order: any hit will do); leaf(child, t1) may
    // lower t1 and returns true to end the search.
    template <bool kNearestFirst, typename Leaf>
    void traverse(const V& origin, const V& direction, C t1, Leaf leaf) const;
    template <bool kNearestFirst, bool kGuarded, typename Leaf>
    void traverse(const SlabRay& ray, C t1, Leaf leaf) const;

    // Which children of node the ray may meet within [0, t1] (bit k for child k), and
    // where it enters each. A slab is computed with at most 3 roundings, so the far end
    // is widened by 2 gamma(3) (pbrt-v4, section 6.8.2). The slabs are clipped at t = 0,
    // not at the query's own start, so that a box holding the origin inside is always
    // met (the tangent roots above; a point on a surface lies inside its box's gap):
    // there each slab's near end is <= 0 and its far end >= 0, signs that the rounding
    // of (plane - o) * inv keeps exactly.
    // kGuarded: the ray's origin is known to be within every guard distance.
    template <bool kGuarded>
    static unsigned meets(const Node& node, const SlabRay& ray, C t1, C (&near)[Width]) {
        constexpr C kEps = std::numeric_limits<C>::epsilon() / 2;
        constexpr C kWiden = 1 + 2 * (3 * kEps / (1 - 3 * kEps));
        C enter[Width], leave[Width], farthest[Width];
        for (int k = 0; k < Width; ++k) enter[k] = 0, leave[k] = t1, farthest[k] = 0;
        for (int a = 0; a < 3; ++a) {
            const C* lo = node.box[0][a];
            const C* hi = node.box[1][a];
            const C from = ray.o[a], scale = ray.inv[a];
            RT_VECTOR_LOOP
            for (int k = 0; k < Width; ++k) {
                const C to_lo = lo[k] - from, to_hi = hi[k] - from;
                const C p = to_lo * scale, q = to_hi * scale;
                const C first = p < q ? p : q, last = (p < q ? q : p) * kWiden;
                enter[k] = first > enter[k] ? first : enter[k];
                leave[k] = last < leave[k] ? last : leave[k];
                if (kGuarded) continue;
                const C reach = std::max(std::abs(to_lo), std::abs(to_hi));
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
        return mask & node.used;
    }

    std::uint32_t collapse(const std::vector<BuildNode<C>>& binary, std::uint32_t b);

    std::vector<Node> nodes_;
    Child root_{0, 0};
    BuildBox<C> bounds_{};                 // of every box
    C guard_ = 0;                          // the smallest guard
    std::vector<Ellipsoid<Real>> items_;   // in leaf order
    std::vector<std::uint32_t> index_;     // items_[k] is the ellipsoid index_[k] of the scene
    std::vector<std::uint32_t> position_;  // and ellipsoid i is items_[position_[i]]
};

template <typename Real, int Width>
template <bool kNearestFirst, typename Leaf>
void Bvh<Real, Width>::traverse(const V& origin, const V& direction, C t1, Leaf leaf) const {
    if (items_.empty()) return;
    SlabRay ray;
    const C d[3] = {C(direction.x), C(direction.y), C(direction.z)};
    for (int a = 0; a < 3; ++a) {
        ray.inv[a] = 1 / d[a];
        // A component below 1 / max (a scene of subnormal numbers) has an infinite
        // inverse, which makes a slab's t = (plane - o) * inv infinite where it is
        // finite, and culls boxes the ray enters: such a ray is tried against every
        // ellipsoid, as by the definition.
        if (d[a] != 0 && !(std::abs(ray.inv[a]) <= std::numeric_limits<C>::max())) {
            leaf(Child{0, static_cast<std::uint32_t>(items_.size())}, t1);
            return;
        }
    }
    ray.o[0] = C(origin.x), ray.o[1] = C(origin.y), ray.o[2] = C(origin.z);
    // Nearly every ray starts within every guard distance (the scene is far smaller than
    // 1e6 of its smallest scale): then no node needs its guards checked.
    C farthest = 0;
    for (int a = 0; a < 3; ++a)
        farthest =
            std::max({farthest, std::abs(bounds_.lo[a] - ray.o[a]), std::abs(bounds_.hi[a] - ray.o[a])});
    if (farthest <= guard_)
        traverse<kNearestFirst, true>(ray, t1, leaf);
    else
        traverse<kNearestFirst, false>(ray, t1, leaf);
}

// Down the tree from the root: at each node the ray goes on into the first child it
// meets (the nearest where kNearestFirst) and leaves the others on the stack, so a
// node met by one child's box only costs no stack traffic (as Embree's traversal).
template <typename Real, int Width>
template <bool kNearestFirst, bool kGuarded, typename Leaf>
void Bvh<Real, Width>::traverse(const SlabRay& ray, C t1, Leaf leaf) const {
    StackEntry stack[kStack];  // NOLINT(cppcoreguidelines-pro-type-member-init): written before read
    int size = 0;
    Child current = root_;
    for (;;) {
        while (current.count == 0) {
            const Node& node = nodes_[current.first];
            C near[Width];
            unsigned mask = meets<kGuarded>(node, ray, t1, near);
            if (mask == 0) break;
            int k = lowest_bit(mask);
            mask &= mask - 1;
            if (!kNearestFirst) {
                for (; mask != 0; mask &= mask - 1) stack[size++] = {node.child[lowest_bit(mask)], 0};
                current = node.child[k];
                continue;
            }
            // The others pushed farthest first, so that the nearest is popped next.
            const int pushed = size;
            for (; mask != 0; mask &= mask - 1) {
                int j = lowest_bit(mask);
                if (near[j] < near[k]) std::swap(j, k);
                int at = size++;
                for (; at > pushed && stack[at - 1].near < near[j]; --at) stack[at] = stack[at - 1];
                stack[at] = {node.child[j], near[j]};
            }
            current = node.child[k];
        }
        if (current.count > 0 && leaf(current, t1)) return;
        // The next entry that may still be met: t1 may have come down since it was pushed.
        do {
            if (size == 0) return;
            --size;
        } while (stack[size].near > t1);
        current = stack[size].child;
    }
}

template <typename Real, int Width>
Bvh<Real, Width>::Bvh(std::vector<Ellipsoid<Real>> ellipsoids, unsigned threads) {
    // Rounding of intersect() in the unit space grows like epsilon(Real) times the
    // distance in units of the smallest scale: as sphere_bounds.h, at most 1e6 smallest
    // scales in double (1e2 in float). The Euclidean distance is at most sqrt(3) times
    // the max-norm one that meets() measures: the guard is half the reach.
    const C reach = std::numeric_limits<Real>::digits > 30 ? C(1e6) : C(1e2);
    std::vector<BuildItem<C>> items(ellipsoids.size());
    for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
        using std::abs;
        const Ellipsoid<Real>& e = ellipsoids[i];
        const C c[3] = {C(e.centre.x), C(e.centre.y), C(e.centre.z)};
        const C s[3] = {abs(C(e.scale.x)), abs(C(e.scale.y)), abs(C(e.scale.z))};
        BuildItem<C>& item = items[i];
        for (int a = 0; a < 3; ++a) {
            // Grown by 4 ulps of the centre too, so that the box's own rounding stays
            // inside the gap even for a small ellipsoid far from the origin; and by the
            // smallest subnormal, as a scale below 500 of them is its own product with
            // 1 + kInflation: a gap of one ulp is still > kInflation of it.
            const C half = s[a] * (1 + C(kInflation)) + abs(c[a]) * 4 * std::numeric_limits<C>::epsilon() +
                           std::numeric_limits<C>::denorm_min();
            item.box.lo[a] = c[a] - half, item.box.hi[a] = c[a] + half;
            item.centre[a] = c[a];
        }
        const C guard = std::min({s[0], s[1], s[2]}) * reach / 2;
        item.guard = guard <= std::numeric_limits<C>::max() ? guard : std::numeric_limits<C>::max();
        item.index = static_cast<std::uint32_t>(i);
    }
    const std::vector<BuildNode<C>> binary = BinaryTreeBuilder<C>().build(items, threads);
    index_.reserve(items.size());
    position_.resize(items.size());
    for (const BuildItem<C>& item : items) {
        position_[item.index] = static_cast<std::uint32_t>(index_.size());
        index_.push_back(item.index);
    }
    std::vector<BuildItem<C>>().swap(items);  // not needed past this: a lower peak
    // The ellipsoids into leaf order in place, cycle by cycle (no second copy).
    std::vector<bool> placed(ellipsoids.size());
    for (std::size_t k = 0; k < ellipsoids.size(); ++k) {
        if (placed[k]) continue;
        const Ellipsoid<Real> first = ellipsoids[k];
        std::size_t j = k;
        for (; index_[j] != k; j = index_[j]) ellipsoids[j] = ellipsoids[index_[j]], placed[j] = true;
        ellipsoids[j] = first, placed[j] = true;
    }
    items_ = std::move(ellipsoids);
    if (binary.empty()) return;
    bounds_ = binary[0].box, guard_ = binary[0].guard;
    // At most one wide node per inner binary node: reserved (pages that are never
    // written cost no memory), so that the list is not copied as it grows.
    nodes_.reserve(binary.size() / 2);
    if (binary[0].count > 0)
        root_ = {binary[0].first, binary[0].count};
    else
        root_ = {collapse(binary, 0), 0};
}

// The wide node for binary inner node b: its children, where an inner one with the
// largest box is replaced by its own two children until there are Width (the "pull up
// the largest" rule of Embree's BVH4 builders).
template <typename Real, int Width>
std::uint32_t Bvh<Real, Width>::collapse(const std::vector<BuildNode<C>>& binary, std::uint32_t b) {
    std::uint32_t lanes[Width] = {binary[b].first, binary[b].first + 1};
    int used = 2;
    while (used < Width) {
        int widest = -1;
        for (int k = 0; k < used; ++k)
            if (binary[lanes[k]].count == 0 &&
                (widest < 0 || binary[lanes[k]].box.half_area() > binary[lanes[widest]].box.half_area()))
                widest = k;
        if (widest < 0) break;
        const std::uint32_t inner = lanes[widest];
        lanes[widest] = binary[inner].first;
        lanes[used++] = binary[inner].first + 1;
    }
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node{};
    for (int k = 0; k < Width; ++k) {  // unused lanes: an empty box, not in used
        for (int a = 0; a < 3; ++a)
            node.box[0][a][k] = std::numeric_limits<C>::max(), node.box[1][a][k] = -node.box[0][a][k];
        node.guard[k] = std::numeric_limits<C>::max();
    }
    node.used = (1U << used) - 1;
    for (int k = 0; k < used; ++k) {
        const BuildNode<C>& child = binary[lanes[k]];
        for (int a = 0; a < 3; ++a) node.box[0][a][k] = child.box.lo[a], node.box[1][a][k] = child.box.hi[a];
        node.guard[k] = child.guard;
        node.child[k] =
            child.count > 0 ? Child{child.first, child.count} : Child{collapse(binary, lanes[k]), 0};
    }
    nodes_[index] = node;
    return index;
}

}  // namespace rt
