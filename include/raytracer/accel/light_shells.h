// Shells: ellipsoids that enclose a light, which a shadow ray to that light from a point
// inside them cannot be blocked by.
//
// WHY: in a mirror room (the eye and the lights inside one large ellipsoid) every shadow
// ray starts inside the room's box, so no bounding volume can cull the room, and every
// ray would solve it; yet an ellipsoid is convex, so a segment from a point inside it (or
// on it) to a light well inside it stays inside and only touches the shell at its start.
// Exactly: with f(t) = |o' + t d'|^2 - 1 in the unit sphere's space, convex in t,
// f(0) <= 1e-10 and f(1) <= -1e-3 give f(t) <= 1e-10 - 1e-3 t < 0 for all t in
// (1e-7, 1], so the roots intersect() computes lie at t < 1e-7 + rounding and beyond
// t = 1 + 1e-4 or so: none in (0.001, 1), intersect()'s "not blocked". Skipping the test
// cannot change an image. Only at double precision or wider, where the rounding of a
// point and of this test is far below 1e-10.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/lanes.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// The two ends of the bound above, on o2 = |(p - centre) / scale|^2 (below 1 inside).
template <typename C>
bool shell_holds_light(C o2) {
    return o2 <= C(1) - C(1e-3);
}
template <typename T>
MaskOf<T> shell_holds_point(const T& o2) {
    return T(1) + T(1e-10) >= o2;
}

// o2 of a point (or of lanes of points) for an ellipsoid of this centre and 1 / scale. A
// product by the reciprocal is fine here: only a bound with a wide margin is decided.
template <typename T, typename C>
T unit_radius2(const Vec3<T>& p, const Vec3<C>& centre, const Vec3<C>& inverse_scale) {
    const Vec3<T> u = (p - Vec3<T>::from(centre)) * Vec3<T>::from(inverse_scale);
    return dot(u, u);
}

// The shells of a scene's lights: at most kMax ellipsoids in all (skipping fewer is
// still exact), each light with the ones that hold it.
template <typename Real>
class LightShells {
public:
    using C = AtLeastDouble<Real>;
    static constexpr int kMax = 4;

    LightShells() = default;

    // geometry.boxes_holding(light, f) calls f(i) for (at least) each ellipsoid i whose
    // box holds the point light (Bvh::boxes_holding()).
    template <typename Geometry>
    LightShells(const Geometry& geometry, const std::vector<Vec3<Real>>& lights) {
        if (std::numeric_limits<Real>::digits < std::numeric_limits<double>::digits) return;
        light_shells_.assign(lights.size(), 0);
        for (std::size_t l = 0; l < lights.size(); ++l)
            geometry.boxes_holding(lights[l], [&](std::uint32_t i) {
                const Ellipsoid<Real>& e = geometry.ellipsoid(i);
                const Vec3<C> centre = Vec3<C>::from(e.centre);
                const Vec3<C> inverse{C(1) / C(e.scale.x), C(1) / C(e.scale.y), C(1) / C(e.scale.z)};
                if (!shell_holds_light(unit_radius2(Vec3<C>::from(lights[l]), centre, inverse))) return;
                int s = 0;
                while (s < count_ && shells_[s].ellipsoid != i) ++s;
                if (s == kMax) return;
                if (s == count_) shells_[count_++] = {i, centre, inverse};
                light_shells_[l] |= 1U << s;
            });
    }

    int count() const { return count_; }
    std::uint32_t ellipsoid(int s) const { return shells_[s].ellipsoid; }
    // The shells that hold light l: bit s for shell s.
    unsigned of_light(std::size_t l) const { return light_shells_.empty() ? 0U : light_shells_[l]; }

    // The lanes of points within shell s, where its lights' shadow rays may skip it.
    template <int N>
    LaneBits holding(int s, const Vec3<Lanes<Real, N>>& points) const {
        return shell_holds_point(unit_radius2(points, shells_[s].centre, shells_[s].inverse_scale));
    }

private:
    struct Shell {
        std::uint32_t ellipsoid;
        Vec3<C> centre, inverse_scale;
    };
    Shell shells_[kMax] = {};
    int count_ = 0;
    std::vector<unsigned> light_shells_;  // per light
};

}  // namespace rt
