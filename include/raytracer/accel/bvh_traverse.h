// The descent of the tree of bvh.h: Bvh::traverse(), for one ray and for a bundle's slab
// ray, which visits the leaves whose boxes the ray may meet (children_met(),
// slab_rays.h); the eye blocks' query on it, Bvh::closest() for an EyeBlock; and the
// leaves whose boxes hold a point, Bvh::boxes_holding().
#pragma once

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "raytracer/accel/bvh.h"
#include "raytracer/bit_scan.h"

namespace rt {

template <typename Real, int Width>
template <typename Bvh<Real, Width>::Visit kVisit, typename Leaf>
void Bvh<Real, Width>::traverse(const OneRay& ray, C t1, Leaf leaf) const {
    if (ellipsoids_.empty()) return;
    if (!ray.sloped)
        leaf(Child{0, static_cast<std::uint32_t>(ellipsoids_.size())}, t1);
    else if (ray.guarded)
        traverse<kVisit, true>(ray.slab, t1, leaf);
    else
        traverse<kVisit, false>(ray.slab, t1, leaf);
}

// Down the tree from the root: at each node the ray goes on into the first child it
// meets (the nearest where kVisit says so) and leaves the others on the stack, so a
// node met by one child's box only costs no stack traffic (as Embree's traversal).
template <typename Real, int Width>
template <typename Bvh<Real, Width>::Visit kVisit, bool kGuarded, typename Leaf>
void Bvh<Real, Width>::traverse(const SlabRay<C>& ray, C t1, Leaf leaf) const {
    StackEntry stack[kStack];  // NOLINT(cppcoreguidelines-pro-type-member-init): written before read
    int size = 0;
    Child current = root_;
    for (;;) {
        while (current.count == 0) {
            const Node& node = nodes_[current.first];
            C near[Width];
            unsigned mask = children_met<kGuarded>(node, ray, t1, near);
            if (mask == 0) break;
            int k = lowest_bit(mask);
            mask &= mask - 1;
            if (kVisit == Visit::AnyOrder) {
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
template <int Rows, int Columns>
void Bvh<Real, Width>::closest(EyeBlock<Real, Rows, Columns>& block) const {
    if (ellipsoids_.empty()) return;
    C d_lo[3], d_hi[3];
    block.directions(d_lo, d_hi);
    const C o[3] = {0, 0, 0};
    SlabRay<C> ray;
    auto add_all = [&] {  // a direction without a finite inverse
        for (std::uint32_t i = 0; i < ellipsoids_.size(); ++i) block.add(ellipsoids_[i], index_[i]);
    };
    if (!make_slab_ray(o, o, d_lo, d_hi, least_direction_, ray)) return add_all();
    if (!guarded(o, o)) {  // the camera beyond some guard: ray by ray, each culled where it may be
        for (int b = 0; b < block.rows(); ++b)
            for (int c = 0; c < block.columns(); ++c)
                block.take(b, c, closest(V{}, block.direction(b, c), kEyeRayMinT));
        return;
    }
    auto descend = [&](const SlabRay<C>& part) {
        const C start = block.tried() ? C(block.farthest()) : std::numeric_limits<C>::infinity();
        traverse<Visit::NearestFirst, true>(part, start, [&](Child leaf, C& t1) {
            for (std::uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
                const BuildBox<C> box = inflated_box<C>(ellipsoids_[i], gaps_);
                if (meets_box(part, box, t1)) block.add(ellipsoids_[i], index_[i], &box);
            }
            if (block.tried()) t1 = C(block.farthest());
            return false;
        });
    };
    // A block whose rays' x or y changes sign (on the image's centre lines) goes down as one
    // bundle a side: a slab ray whose directions run both ways along an axis keeps only one
    // of its two entry bounds there (make_slab_ray()), so that slab would cull no box on
    // the other side, however far (random 100k: 90-125 us such a block, against 10 us).
    // An ellipsoid met by two sides is added twice, which changes no pixel's hit.
    const bool x_both = d_lo[0] < 0 && d_hi[0] >= 0, y_both = d_lo[1] < 0 && d_hi[1] >= 0;
    if (!x_both && !y_both) return descend(ray);
    for (const int x_side : {-1, 1})
        for (const int y_side : {-1, 1}) {
            if ((!x_both && x_side > 0) || (!y_both && y_side > 0)) continue;
            C lo[3], hi[3];
            if (!block.directions(lo, hi, x_both ? x_side : 0, y_both ? y_side : 0)) continue;
            if (!make_slab_ray(o, o, lo, hi, least_direction_, ray)) return add_all();
            descend(ray);
        }
}

template <typename Real, int Width>
template <typename F>
void Bvh<Real, Width>::boxes_holding(const V& point, F f) const {
    const C p[3] = {C(point.x), C(point.y), C(point.z)};
    std::vector<Child> to_visit = {root_};
    while (!to_visit.empty()) {
        const Child child = to_visit.back();
        to_visit.pop_back();
        for (std::uint32_t k = child.first; k < child.first + child.count; ++k) f(index_[k]);
        if (child.count > 0 || ellipsoids_.empty()) continue;
        const Node& node = nodes_[child.first];
        for (int k = 0; k < Width; ++k) {
            bool holds = (node.used >> k) & 1U;
            for (int a = 0; a < 3; ++a)
                holds = holds && node.box[0][a][k] <= p[a] && p[a] <= node.box[1][a][k];
            if (holds) to_visit.push_back(node.child[k]);
        }
    }
}

}  // namespace rt
