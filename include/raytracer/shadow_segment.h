// The shadow rule of SPEC section 5: an ellipsoid blocks the light when the segment from
// the lit point to the light, point + t (light - point), meets it at 0.001 < t < 1.
// Every shadow test of the renderer (scalar, packets, prefilters, light cones) gives this
// function's answer; the culling tests hold each shortcut to it.
#pragma once

#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

inline constexpr double kShadowRayMinT = 0.001;  // the keys need 0.001, not 0.0001

// The segment's ends are decided as Tracer::closest() decides the near plane: a root
// within 8 scene ulps of 0.001 or of the light (t = 1) is at it and does not block; a
// light on the surface itself gets a root of exactly 1 (unit_sphere_roots()). So every
// precision decides a light on a surface as exact arithmetic does.
template <typename Real>
bool blocks_segment(const Ellipsoid<Real>& e, const Vec3<Real>& point, const Vec3<Real>& to_light) {
    const Real min_t = Real(kShadowRayMinT) * (Real(1) + Real(8) * scene_epsilon<Real>());
    const Real max_t = Real(1) - Real(8) * scene_epsilon<Real>();
    const Roots<Real> r = intersect(e, point, to_light);
    return r.hit && ((r.near > min_t && r.near < max_t) || (r.far > min_t && r.far < max_t));
}

}  // namespace rt
