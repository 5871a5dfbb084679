// An ellipsoid is the unit sphere scaled by s about its centre C. A ray o + t d meets it
// where the mapped ray (o - C)/s + t d/s meets the unit sphere; t is the same in both
// spaces (SPEC section 4), so no 4x4 matrix is needed for an axis-aligned ellipsoid.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "raytracer/scene.h"
#include "raytracer/scene_precision.h"
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

// Both ray parameters where the ray meets the surface, near <= far; hit is false when
// the ray misses it.
template <typename Real>
struct Roots {
    bool hit = false;
    Real near = 0, far = 0;
};

// Solves |o' + t d'|^2 = 1 with o' = (o - C)/s and d' = d/s, written as
// a t^2 + 2 b t + c = 0 with a = d'.d', b = o'.d' (half the linear term), c = o'.o' - 1.
//
// Discriminant. b^2 - a c cancels catastrophically when the ellipsoid is far away or
// thin: b^2 and a c are then ~|o'|^2 and nearly equal, so their rounding error, an ulp
// of |o'|^2, swamps a difference below 1 once |o'| passes ~1/sqrt(epsilon): ~4e3 radii
// in float, ~7e7 in double. Instead it is computed from the vector l = o' - (b/a) d' from the
// centre to the ray, perpendicular to it: b^2 - a c = a (1 - l.l), where 1 - l.l has no
// cancellation except near tangency, where it is inherent (E. Haines, J. Guenther,
// T. Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
// Gems, Apress 2019, ch. 7). The absolute error of l is a few ulps of |o'|,
// the same as the rounding already in o' itself, so the result is the exact one for an
// ellipsoid moved by a few ulps of its distance: backward stable.
//
// Roots. -b +- sqrt(disc) cancels for the root whose sign differs from -b; instead
// q = -(b + sign(b) sqrt(disc)), t = q/a and t = c/q, both free of cancellation
// (W. H. Press et al., Numerical Recipes, 3rd ed., section 5.6;
// D. Goldberg, "What Every Computer Scientist Should Know About Floating-Point
// Arithmetic", ACM Computing Surveys 23(1), 1991, section 1.4).
//
// c = o'.o' - 1 cancels when the origin lies on the surface (shadow and reflected
// rays), but benignly: its absolute error, a few ulps of |o'|^2, is that of the origin
// itself, and it only enters the root c/q ~ 0 that the thresholds 0.001 and 0.0001
// (SPEC section 5) discard. For a ray grazing the surface from it (a light on the
// terminator) q is small too, but then the light's contribution N.L is as small.
//
// Tangency. An exactly tangent ray is a hit (SPEC section 4). Rounding moves 1 - l.l by
// about 2 |delta l| ~ a few ulps of |o'|, in either direction; a value within
// 4 ulps(scene) of (1 + |o'|) below zero is taken as zero. The max-norm bounds |o'| to
// within sqrt(3) and needs no square root.
//
// intersect() is mapped_origin() and intersect_mapped() in one: rays from one origin
// (every eye ray) share o' and c, which the caller may compute once with mapped_origin().
template <typename Real>
struct MappedOrigin {
    Vec3<Real> o;  // (origin - C) / s
    Real c;        // o'.o' - 1
};

template <typename Real>
MappedOrigin<Real> mapped_origin(const Ellipsoid<Real>& e, const Vec3<Real>& origin) {
    const Vec3<Real> o = (origin - e.centre) / e.scale;
    return {o, dot(o, o) - Real(1)};
}

template <typename Real>
Roots<Real> intersect_mapped(const Ellipsoid<Real>& e, const MappedOrigin<Real>& m,
                             const Vec3<Real>& direction) {
    using std::abs;
    using std::sqrt;
    const Vec3<Real>& o = m.o;
    const Real c = m.c;
    const Vec3<Real> d = direction / e.scale;
    const Real a = dot(d, d);
    const Real b = dot(o, d);
    const Vec3<Real> l = o - d * (b / a);
    Real unit_disc = Real(1) - dot(l, l);  // (b^2 - a c) / a
    if (unit_disc < 0) {
        const Real distance = std::max(abs(o.x), std::max(abs(o.y), abs(o.z)));  // |o'| within sqrt(3)
        if (unit_disc < -Real(4) * scene_epsilon<Real>() * (Real(1) + distance)) return {};
        unit_disc = 0;  // tangent
    }
    const Real root = sqrt(a * unit_disc);
    const Real q = -(b + std::copysign(root, b));
    if (q == 0) return {true, 0, 0};  // the origin lies on the surface and the ray grazes it
    Real t1 = q / a, t2 = c / q;
    if (t1 > t2) std::swap(t1, t2);
    return {true, t1, t2};
}

template <typename Real>
Roots<Real> intersect(const Ellipsoid<Real>& e, const Vec3<Real>& origin, const Vec3<Real>& direction) {
    return intersect_mapped(e, mapped_origin(e, origin), direction);
}

// The unit outward normal at a point P on the surface.
template <typename Real>
Vec3<Real> outward_normal(const Ellipsoid<Real>& e, const Vec3<Real>& point) {
    return normalize((point - e.centre) / e.scale_squared);
}

}  // namespace rt
