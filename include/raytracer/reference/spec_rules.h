// The rules of SPEC sections 3-5 that decide, per ray and ellipsoid, what a root means:
// which root an eye or reflected ray sees, and whether a shadow ray is blocked, with
// the constants the course keys fix. Every path of the renderer (the flat sweep of
// packet_tracer.h and its vector lanes, the geometry queries of brute_force.h and bvh.h)
// decides with these, so that all agree bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/reference/ellipsoid.h"
#include "raytracer/scene.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// Epsilons and limits that the course keys fix (SPEC sections 3 and 5).
inline constexpr double kEyeRayMinT = 1.0;       // the near plane is at t = 1
inline constexpr double kShadowRayMinT = 0.001;  // the keys need 0.001, not 0.0001
inline constexpr double kReflectedRayMinT = 0.0001;
inline constexpr int kMaxReflections = 3;

// Where column c of `columns` and row r of `rows` look through the near plane: the
// top-left corner of the pixel, not its centre (the keys demand it; SPEC section 3).
template <typename Real>
Real pixel_x(Real left, Real right, int c, int columns) {
    return left + (right - left) * Real(c) / Real(columns);
}
template <typename Real>
Real pixel_y(Real top, Real bottom, int r, int rows) {
    return top - (top - bottom) * Real(r) / Real(rows);
}
// pixel_x() of every column of the scene's image, a table the fast paths make once
// rather than computing it per row (the reference calls pixel_x() per pixel).
template <typename Real>
std::vector<Real> column_xs(const Scene& scene) {
    std::vector<Real> x(static_cast<std::size_t>(scene.columns));
    for (int c = 0; c < scene.columns; ++c)
        x[static_cast<std::size_t>(c)] = pixel_x(Real(scene.left), Real(scene.right), c, scene.columns);
    return x;
}

// A ray parameter a root must lie beyond to be visible, for a ray that starts at
// min_t. A root computed within a few ulps of min_t cannot be told from one at min_t,
// and one at min_t is not visible (the hit must lie beyond it). The roots a decimal
// scene puts at exactly t = 1 (keyIllum's rim pixels (240,345), (360,345), (345,240),
// (345,360): a 3-4-5 triangle, which double rounding puts 2 ulps above 1; a light on a
// surface) the solver itself sets to 1 (unit_sphere_roots.h, the point at t = 1); this
// margin is for the roots no such test settles, at 0.001, 0.0001 and 1. The ulps are
// those of the scene's double numbers, whatever Real is (scene_precision.h), so that
// long double decides as double does.
inline constexpr int kRootUlps = 8;  // a root this many scene ulps from a bound is at it
template <typename Real>
Real visible_beyond(Real min_t) {
    return min_t * (Real(1) + Real(kRootUlps) * scene_epsilon<Real>());
}

// The root a ray sees of an ellipsoid it meets, given visible_beyond(): the near root
// when it lies beyond the limit, else the far one (the ray starts inside, or the near
// plane cuts the ellipsoid: it is seen hollow). Returns false when neither is visible.
template <typename Real>
bool visible_root(const Roots<Real>& r, Real beyond, Real& t, bool& inside) {
    if (r.hit == 0) return false;
    inside = !(r.near > beyond);
    t = inside ? r.far : r.near;
    return t > beyond;
}

// The shadow rule of SPEC section 5: ellipsoid e blocks the light when the segment from
// the lit point to the light, point + t (light - point), meets it at 0.001 < t < 1. Its
// ends are decided as the near plane is: a root within kRootUlps of 0.001 or of the
// light (t = 1) is at it and does not block; a light on the surface itself gets a root
// of exactly 1 (unit_sphere_roots.h). So every precision decides a light on a surface
// as exact arithmetic does.
template <typename Real>
bool blocks_segment(const Roots<Real>& r) {
    const Real min_t = visible_beyond(Real(kShadowRayMinT));
    const Real max_t = Real(1) - Real(kRootUlps) * scene_epsilon<Real>();
    return r.hit != 0 && ((r.near > min_t && r.near < max_t) || (r.far > min_t && r.far < max_t));
}
template <typename Real>
bool blocks_segment(const Ellipsoid<Real>& e, const Vec3<Real>& point, const Vec3<Real>& to_light) {
    return blocks_segment(intersect(e, point, to_light));
}

// Whether the specular term Ks Ip (R.V)^n of an ellipsoid is exactly zero for every
// light: Ks = 0, with pow finite (R.V <= 1 + a few ulps and 0 <= n <= 1e6). Shading
// then skips it; adding it would change at most the sign of a zero channel.
template <typename Real>
bool specular_is_zero(const Ellipsoid<Real>& e) {
    return e.ks == 0 && e.shininess >= 0 && e.shininess <= Real(1e6);
}

// No ellipsoid, where an ellipsoid's index goes (greater than any index): what a
// closest-hit query answers for a ray that hits nothing, and what an any-hit query's
// hint holds before any shadow ray was blocked (whitted.h, blocker_hints.h).
inline constexpr std::uint32_t kNoEllipsoid = 0xFFFFFFFFU;

// The answer of a closest-hit query: the ellipsoid a ray sees first, at t.
template <typename Real>
struct NearestHit {
    Real t = 0;
    std::uint32_t ellipsoid = kNoEllipsoid;
    bool inside = false;  // the far root was taken: the ray sees the inside

    bool found() const { return ellipsoid != kNoEllipsoid; }
    // Whether root t of ellipsoid i is to replace this hit. Equal roots go to the lower
    // index, as in a loop over the ellipsoids in the file's order, whatever order a
    // query visits them in.
    bool replaced_by(Real root, std::uint32_t i) const {
        return !found() || root < t || (root == t && i < ellipsoid);
    }
    // Takes the root the ray sees of ellipsoid i (visible_root() beyond `beyond`) where
    // it is to replace this hit; whether it did.
    bool offer(const Roots<Real>& roots, Real beyond, std::uint32_t i) {
        Real root;
        bool seen_inside;
        if (!visible_root(roots, beyond, root, seen_inside) || !replaced_by(root, i)) return false;
        *this = {root, i, seen_inside};
        return true;
    }
};

}  // namespace rt
