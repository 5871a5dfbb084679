// Per ellipsoid i and light l, the ellipsoids that can block a shadow ray from any point
// of i's bounding sphere to l, as an EllipsoidSet's words, computed once.
//
// WHY: a packet's shadow candidates are often known in advance: in the course scenes a
// sphere's light often has no other sphere anywhere near the way, and in the mirror
// room the room encloses every small ellipsoid and every light. Two exact reasons to
// leave ellipsoid j out for all points P of the bounding sphere S_i (centre c, radius R):
// - every segment from such a P to L lies within distance R of the segment from c to
//   L (P + t (L - P) is (1 - t)(P - c) away from c + t (L - c)), so j's bounding sphere
//   (radius r_j, inflated by 1e-3 over the ellipsoid: sphere_bounds.h) cannot meet it
//   when dist(c_j, [c, L]) > R + r_j; then intersect() finds no root on the segment;
// - j encloses the light (Enclosures::light_within()) and S_i with a margin of 1e-6 in
//   j's unit space: then Enclosures::point_within() holds for each point of S_i, and
//   contains_segment() clears j.
// The caller checks that each lane's point lies in S_i (hit points lie on the
// ellipsoid, far inside the inflation) before it uses the set. The rounding here is
// covered by a slack of 1e-9 of the coordinates' magnitudes (the errors are a few 1e-16
// of them).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/compiler.h"
#include "raytracer/flat_sweep/bounding_sphere.h"
#include "raytracer/flat_sweep/ellipsoid_set.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"

namespace rt {

template <typename Real>
class PairBlockers {
public:
    using C = AtLeastDouble<Real>;
    PairBlockers() = default;

    // spheres: the inflated bounding spheres; encloses(l, j): Enclosures::light_within(l, j).
    template <typename Encloses>
    PairBlockers(const std::vector<BoundingSphere<C>>& spheres,
                 const std::vector<Ellipsoid<Real>>& ellipsoids, const std::vector<Vec3<C>>& lights,
                 Encloses encloses)
        : lights_(lights.size()) {
        using std::abs;
        const std::size_t n = spheres.size();
        if (n > WideSet::kCapacity) return;
        words_ = set_words(n);
        sets_.assign(n * lights_ * words_, 0);
        // The spheres as a structure of arrays, padded to a multiple of 8 (the padding's
        // bits are cleared below), so that the loop over j runs as vector instructions.
        const std::size_t padded = (n + 7) / 8 * 8;
        std::vector<C> x(padded), y(padded), z(padded), radius(padded), extent(padded);
        for (std::size_t j = 0; j < n; ++j) {
            const BoundingSphere<C>& sj = spheres[j];
            x[j] = sj.x, y[j] = sj.y, z[j] = sj.z, radius[j] = sj.radius;
            extent[j] = abs(sj.x) + abs(sj.y) + abs(sj.z) + sj.radius;
        }
        for (std::size_t i = 0; i < n; ++i) {
            const BoundingSphere<C>& si = spheres[i];
            for (std::size_t l = 0; l < lights_; ++l) {
                const Vec3<C>& light = lights[l];
                const C ux = light.x - si.x, uy = light.y - si.y, uz = light.z - si.z;
                const C uu = ux * ux + uy * uy + uz * uz;
                const C inverse = uu > 0 ? C(1) / uu : C(0);
                const C magnitude = abs(si.x) + abs(si.y) + abs(si.z) + si.radius + abs(light.x) +
                                    abs(light.y) + abs(light.z);
                WideSet set;
                for (std::size_t start = 0; start < padded; start += 8) {
                    std::uint64_t eight = 0;  // ellipsoids start to start + 7
                    RT_VECTOR_LOOP
                    for (std::size_t k = 0; k < 8; ++k) {
                        const std::size_t j = start + k;
                        const C wx = x[j] - si.x, wy = y[j] - si.y, wz = z[j] - si.z;
                        const C s = (wx * ux + wy * uy + wz * uz) * inverse;
                        const C t = s > 0 ? (s < 1 ? s : C(1)) : C(0);
                        const C ex = wx - t * ux, ey = wy - t * uy, ez = wz - t * uz;
                        const C reach = si.radius + radius[j] + C(kSlack) * (magnitude + extent[j]);
                        // Kept where not clearly beyond reach (NaN: kept).
                        eight |= ex * ex + ey * ey + ez * ez > reach * reach ? 0 : kBit[k];
                    }
                    if (n - start < 8) eight &= (std::uint64_t(1) << (n - start)) - 1;  // not padding
                    set.insert_bits(start, eight);
                }
                // Of those, the ones that enclose the light and this whole sphere.
                WideSet kept;
                set.for_each([&](std::size_t j) {
                    if (j == i || !encloses(l, j) || !encloses_sphere(ellipsoids[j], si)) kept.insert(j);
                });
                kept.to_words(&sets_[(i * lights_ + l) * words_], words_);
            }
        }
    }

    bool usable() const { return !sets_.empty(); }
    // The set of ellipsoid i and light l (usable() only), in a Set at least as wide as
    // set_words().
    template <typename Set>
    Set set(std::size_t i, std::size_t l) const {
        return Set::from_words(&sets_[(i * lights_ + l) * words_], words_);
    }

private:
    static constexpr double kSlack = 1e-9;
    static constexpr std::uint64_t kBit[8] = {1, 2, 4, 8, 16, 32, 64, 128};

    // Whether ellipsoid e holds the sphere s with a margin of 1e-6 in e's unit space.
    static bool encloses_sphere(const Ellipsoid<Real>& e, const BoundingSphere<C>& s) {
        using std::abs;
        using std::sqrt;
        const C sx = abs(C(e.scale.x)), sy = abs(C(e.scale.y)), sz = abs(C(e.scale.z));
        const C ox = (s.x - C(e.centre.x)) / sx, oy = (s.y - C(e.centre.y)) / sy,
                oz = (s.z - C(e.centre.z)) / sz;
        return sqrt(ox * ox + oy * oy + oz * oz) + s.radius / std::min({sx, sy, sz}) <= C(1) - C(1e-6);
    }

    std::size_t lights_ = 0, words_ = 0;
    std::vector<std::uint64_t> sets_;  // [(ellipsoid * lights + light) * words_ + word]
};

}  // namespace rt
