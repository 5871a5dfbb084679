// An ellipsoid is the unit sphere scaled by s about its centre C. A ray o + t d meets it
// where the mapped ray (o - C)/s + t d/s meets the unit sphere; t is the same in both
// spaces (SPEC section 4), so no 4x4 matrix is needed for an axis-aligned ellipsoid.
#pragma once

#include <cmath>
#include <limits>

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
// The discriminant b^2 - a c cancels catastrophically when the ellipsoid is far away
// or thin (b^2 and a c are then huge and nearly equal). Instead it is computed from the
// vector l = o' - (b/a) d' that runs from the centre perpendicular to the ray:
// b^2 - a c = a (1 - l.l), which has no such cancellation (Haines, Guenther and
// Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
// Gems, 2019, ch. 7). The two roots avoid -b +- sqrt(...) cancellation by taking
// q = -(b + sign(b) sqrt(disc)) and t = q/a, t = c/q (Press et al., Numerical Recipes,
// section 5.6).
template <typename Real>
Roots<Real> intersect(const Ellipsoid<Real>& e, const Vec3<Real>& origin, const Vec3<Real>& direction) {
    using std::sqrt;
    const Vec3<Real> o = (origin - e.centre) / e.scale;
    const Vec3<Real> d = direction / e.scale;
    const Real a = dot(d, d);
    const Real b = dot(o, d);
    const Real c = dot(o, o) - Real(1);
    const Vec3<Real> l = o - d * (b / a);
    Real unit_disc = Real(1) - dot(l, l);  // (b^2 - a c) / a
    // An exactly tangent ray is a hit (SPEC section 4); rounding may leave the exact
    // zero a few ulps below it, so a value that small counts as zero.
    if (unit_disc < 0) {
        if (unit_disc < -Real(4) * std::numeric_limits<Real>::epsilon()) return {};
        unit_disc = 0;
    }
    const Real root = sqrt(a * unit_disc);
    const Real q = -(b + std::copysign(root, b));
    if (q == 0) return {true, 0, 0};  // the origin lies on the surface and the ray grazes it
    Real t1 = q / a, t2 = c / q;
    if (t1 > t2) std::swap(t1, t2);
    return {true, t1, t2};
}

// The unit outward normal at a point P on the surface.
template <typename Real>
Vec3<Real> outward_normal(const Ellipsoid<Real>& e, const Vec3<Real>& point) {
    return normalize((point - e.centre) / e.scale_squared);
}

}  // namespace rt
