// Conservative culling of ray/ellipsoid tests by bounding spheres, so that the exact
// intersect() runs only where it could report a hit.
//
// WHY: intersect() costs seven divisions and a square root per ray and ellipsoid; a ray
// that clearly misses a slightly inflated bounding sphere (or has it wholly behind its
// origin) is rejected here with a few multiplications and no division. The sphere of an
// ellipsoid is centred on it with radius max|s| (1 + kCullingGap); it contains the
// ellipsoid with a gap of at least kCullingGap in the unit sphere's space, far more than
// the rounding of intersect() (a few ulps, plus its tangent bound: at most about
// 110 eps (1 + |o'|), 2.4e-8 within the reach below; exact_culling.h states it, bvh.h
// derives it). So every culled test is one that intersect() would have answered "no
// usable root", and images stay bit-identical. Where the ray's origin is so far from an
// ellipsoid, relative to its smallest scale, that rounding could approach that gap,
// nothing is culled.
//
// The arrays are a structure of arrays, so that the per-ray loop over all ellipsoids
// vectorises (GCC -O2/-O3: packed multiplies and compares, no gathers).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/accel/exact_culling.h"
#include "raytracer/compiler.h"
#include "raytracer/flat_sweep/bounding_sphere.h"
#include "raytracer/flat_sweep/ray_cone.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
class SphereBounds {
public:
    using C = AtLeastDouble<Real>;

    SphereBounds() = default;

    explicit SphereBounds(const std::vector<Ellipsoid<Real>>& ellipsoids) {
        const C reach = C(culling_reach<Real>());  // in smallest scales (exact_culling.h)
        const std::size_t n = ellipsoids.size();
        cx_.resize(n), cy_.resize(n), cz_.resize(n), radius_.resize(n), radius2_.resize(n), guard2_.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const Ellipsoid<Real>& e = ellipsoids[i];
            using std::abs;
            const C sx = abs(C(e.scale.x)), sy = abs(C(e.scale.y)), sz = abs(C(e.scale.z));
            const C radius = std::max({sx, sy, sz}) * (C(1) + kCullingGap);
            const C smallest = std::min({sx, sy, sz}) * reach;
            cx_[i] = C(e.centre.x), cy_[i] = C(e.centre.y), cz_[i] = C(e.centre.z);
            radius_[i] = radius;
            radius2_[i] = radius * radius;
            guard2_[i] = smallest * smallest;
        }
    }

    std::size_t size() const { return cx_.size(); }

    // The inflated bounding sphere of ellipsoid i.
    BoundingSphere<C> sphere(std::size_t i) const { return {cx_[i], cy_[i], cz_[i], radius_[i]}; }
    // All of them, in the ellipsoids' order (for the tables built from them).
    std::vector<BoundingSphere<C>> spheres() const {
        std::vector<BoundingSphere<C>> all;
        all.reserve(size());
        for (std::size_t i = 0; i < size(); ++i) all.push_back(sphere(i));
        return all;
    }

    // Whether every ellipsoid is within the guard distance of every point of the box
    // [lo, hi]: then rounding cannot approach the inflation for any ray starting there.
    bool guards(const Vec3<C>& lo, const Vec3<C>& hi) const {
        for (std::size_t i = 0; i < size(); ++i)
            if (!guards(lo, hi, i)) return false;
        return true;
    }
    // The same for ellipsoid i alone.
    bool guards(const Vec3<C>& lo, const Vec3<C>& hi, std::size_t i) const {
        {
            using std::abs;
            const C dx = std::max(abs(lo.x - cx_[i]), abs(hi.x - cx_[i]));
            const C dy = std::max(abs(lo.y - cy_[i]), abs(hi.y - cy_[i]));
            const C dz = std::max(abs(lo.z - cz_[i]), abs(hi.z - cz_[i]));
            return dx * dx + dy * dy + dz * dz <= guard2_[i];
        }
    }

    // For N rays, ray k from (ox, oy, oz)[k] along (dx, dy, dz)[k] (t > 0): writes to
    // listed, in increasing order, the ellipsoids that some ray may hit (the candidates),
    // and returns how many; for each such i, bit k of lanes[i] is set where ray k may hit
    // it. Loops over the lanes that GCC vectorises (one pass over the ellipsoids for all
    // rays instead of one per ray), after the spheres that no ray can meet are ruled out
    // for the whole packet (RayCone: such a sphere's ellipsoid gives no ray a root, by
    // the inflation argument above, so the nearest hits stay the same). lanes, listed,
    // cone_misses (per sphere, not 0 where the cone misses it): size() entries.
    template <int N>
    std::size_t candidate_lanes(const Real* ox, const Real* oy, const Real* oz, const Real* dx,
                                const Real* dy, const Real* dz, std::uint32_t* lanes, std::uint32_t* listed,
                                C* cone_misses) const {
        static_assert(N <= 32, "one bit per lane");
        const std::size_t n = size();
        std::size_t kept = 0;  // the spheres some ray may meet, in listed
        const RayCone<C> cone = RayCone<C>::template of<N>(ox, oy, oz, dx, dy, dz);
        if (cone.usable) {
            for (std::size_t i = 0; i < n; ++i)
                cone_misses[i] = cone.misses(cx_[i], cy_[i], cz_[i], radius_[i], guard2_[i]);
            for (std::size_t i = 0; i < n; ++i) {
                listed[kept] = static_cast<std::uint32_t>(i);
                kept += cone_misses[i] == 0;
            }
        } else {
            for (std::size_t i = 0; i < n; ++i) listed[i] = static_cast<std::uint32_t>(i);
            kept = n;
        }
        C x[N], y[N], z[N], u[N], v[N], w[N], dd[N];
        std::uint32_t bit[N];
        for (int k = 0; k < N; ++k) {
            x[k] = C(ox[k]), y[k] = C(oy[k]), z[k] = C(oz[k]);
            u[k] = C(dx[k]), v[k] = C(dy[k]), w[k] = C(dz[k]);
            dd[k] = u[k] * u[k] + v[k] * v[k] + w[k] * w[k];
            bit[k] = std::uint32_t(1) << k;
        }
        std::size_t count = 0;
        for (std::size_t a = 0; a < kept; ++a) {
            const std::uint32_t i = listed[a];
            const C cx = cx_[i], cy = cy_[i], cz = cz_[i], radius2 = radius2_[i], guard2 = guard2_[i];
            std::uint32_t set = 0;
            RT_VECTOR_LOOP
            for (int k = 0; k < N; ++k) {
                const C px = x[k] - cx, py = y[k] - cy, pz = z[k] - cz;
                const C p2 = px * px + py * py + pz * pz;
                const C b = px * u[k] + py * v[k] + pz * w[k];
                const C cull = culled(in_reach(p2, radius2, guard2), b, dd[k], p2 - radius2);
                set |= cull == 0 ? bit[k] : 0;
            }
            lanes[i] = set;
            listed[count] = i;  // count <= a: in place
            count += set != 0;
        }
        return count;
    }

private:
    // 1 when the origin, at squared distance p2 from the centre, is outside the sphere
    // but within the guard distance (where culling is allowed), else 0.
    static C in_reach(C p2, C radius2, C guard2) { return p2 > radius2 && p2 <= guard2 ? C(1) : C(0); }

    // Positive when the ray misses the sphere or the sphere lies wholly behind the origin,
    // else 0; only decided in reach (then b > 0 puts the whole sphere at t < 0, and a
    // negative discriminant b^2 - dd c means the line misses it). b = (origin - centre).d,
    // dd = d.d, c = |origin - centre|^2 - radius^2. The conditions are numbers, not bools,
    // joined by * and +: that form is branch-free, which GCC's vectoriser needs.
    static C culled(C in_reach, C b, C dd, C c) {
        return in_reach * ((b > 0 ? C(1) : C(0)) + (b * b < dd * c ? C(1) : C(0)));
    }

    std::vector<C> cx_, cy_, cz_, radius_, radius2_, guard2_;
};

}  // namespace rt
