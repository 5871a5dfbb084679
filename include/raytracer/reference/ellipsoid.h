// An ellipsoid is the unit sphere scaled by s about its centre C. A ray o + t d meets it
// where the mapped ray (o - C)/s + t d/s meets the unit sphere; t is the same in both
// spaces (SPEC section 4), so no 4x4 matrix is needed for an axis-aligned ellipsoid.
#pragma once

#include <vector>

#include "raytracer/compiler.h"
#include "raytracer/reference/unit_sphere_roots.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real>
struct Ellipsoid {
    Vec3<Real> centre;
    Vec3<Real> scale;
    Vec3<Real> scale_squared;  // the normal at P is (P - C) / s^2
    Vec3<Real> colour;
    Real ka, kd, ks, kr, shininess;
};

template <typename Real>
Ellipsoid<Real> make_ellipsoid(const SphereSpec& s) {
    const auto scale = Vec3<Real>::from(s.scale);
    return {Vec3<Real>::from(s.centre),
            scale,
            scale * scale,
            Vec3<Real>::from(s.colour),
            static_cast<Real>(s.ka),
            static_cast<Real>(s.kd),
            static_cast<Real>(s.ks),
            static_cast<Real>(s.kr),
            static_cast<Real>(s.shininess)};
}

// The scene's ellipsoids, in its order.
template <typename Real>
std::vector<Ellipsoid<Real>> make_ellipsoids(const Scene& scene) {
    std::vector<Ellipsoid<Real>> all;
    all.reserve(scene.spheres.size());
    for (const SphereSpec& s : scene.spheres) all.push_back(make_ellipsoid<Real>(s));
    return all;
}

// Solves |o' + t d'|^2 = 1 with o' = (o - C)/s and d' = d/s by the one root solver
// (unit_sphere_roots.h: unit_line(), then unit_roots() where the line meets the sphere),
// whose comment gives the scaling, the discriminant, its error bound (the tangency rule)
// and the roots.
//
// intersect() is mapped_origin() and intersect_mapped() in one: rays from one origin
// share o' and c, which a caller may compute once with mapped_origin() (the flat
// sweep's eye rays, eye_rays.h, and the tests of them).
template <typename Real>
struct MappedOrigin {
    Vec3<Real> o;  // (origin - C) / s
    Real c;        // o'.o' - 1 (infinite where it overflows; unit_sphere_roots() copes)
};

// A point mapped into the unit space of the ellipsoid of this centre and scale, for one
// ray or lanes (T = Lanes: exact_culling.h's own_abs_c()).
template <typename T>
RT_ALWAYS_INLINE MappedOrigin<T> mapped_point(const Vec3<T>& point, const Vec3<T>& centre,
                                              const Vec3<T>& scale) {
    const Vec3<T> o = (point - centre) / scale;
    return {o, dot(o, o) - T(1)};
}

template <typename Real>
MappedOrigin<Real> mapped_origin(const Ellipsoid<Real>& e, const Vec3<Real>& origin) {
    return mapped_point(origin, e.centre, e.scale);
}

template <typename Real>
Roots<Real> intersect_mapped(const Ellipsoid<Real>& e, const MappedOrigin<Real>& m,
                             const Vec3<Real>& direction) {
    const Vec3<Real> d = direction / e.scale;
    const UnitLine<Real> line = unit_line(m.o.x, m.o.y, m.o.z, d.x, d.y, d.z);
    if (line.hit == 0) return {};  // the line misses the unit sphere: hit, near and far 0
    return unit_roots(line, m.c);
}

template <typename Real>
Roots<Real> intersect(const Ellipsoid<Real>& e, const Vec3<Real>& origin, const Vec3<Real>& direction) {
    return intersect_mapped(e, mapped_origin(e, origin), direction);
}

}  // namespace rt
