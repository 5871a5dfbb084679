// The shading arithmetic of SPEC section 5, written once for one ray (T = Real: the
// reference, whitted.h) and for lanes (T = Lanes<Real, N>, lanes.h: the tree's tiles,
// whitted_tiles.h, and the flat sweep's packets, hit_packet.h; finish_lanes.h sets a
// Finish's lanes): a hit's point, normal and direction to the viewer, a light's ray, and
// the diffuse and specular terms of a light that reaches the point. The same operations
// in the same order, so a lane's colour is the scalar's, bit for bit.
//
// The terms are multiplied in the order the handout writes them: Ka*Ia*O, Kd*Ip*(N.L)*O
// and Ks*Ip*(R.V)^n; a different order moves a few pixels across a truncation step. The
// specular term is added only where it is not exactly zero (Ks = 0 or R.V <= 0: adding
// it would change at most the sign of a zero channel); one ray branches on that, lanes
// select (masks.h).
#pragma once

#include <cstdint>
#include <vector>

#include "raytracer/compiler.h"
#include "raytracer/image.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/masks.h"
#include "raytracer/reference/power.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

namespace rt {

// A LIGHT of the scene in the renderer's precision; the scene's lights as such, and
// their positions.
template <typename Real>
struct PointLight {
    Vec3<Real> position, intensity;
};
template <typename Real>
std::vector<PointLight<Real>> point_lights(const Scene& scene) {
    std::vector<PointLight<Real>> lights;
    lights.reserve(scene.lights.size());
    for (const LightSpec& l : scene.lights)
        lights.push_back({Vec3<Real>::from(l.position), Vec3<Real>::from(l.intensity)});
    return lights;
}
template <typename Real>
std::vector<Vec3<Real>> positions_of(const std::vector<PointLight<Real>>& lights) {
    std::vector<Vec3<Real>> positions;
    positions.reserve(lights.size());
    for (const PointLight<Real>& l : lights) positions.push_back(l.position);
    return positions;
}

// What shading needs of an ellipsoid's material, per ray for lanes.
template <typename T>
struct Finish {
    Vec3<T> colour;         // O
    T kd, ks, shininess;    // Kd, Ks, n
    IntegerOf<T> exponent;  // whole_exponent(n): -1 where pow() is needed
    // The whole exponent that every lane has, where known (for one ray, exponent), else
    // -1. Known, one loop of scalar tests serves all lanes; else each lane's own
    // exponent takes a mask a step (power.h).
    std::int32_t shared_exponent;
    MaskOf<T> specular;  // not specular_is_zero(): a specular term may show
};

// Ellipsoid e's Finish (its exponent and specular mask computed here: a few operations).
template <typename Real>
Finish<Real> finish_of(const Ellipsoid<Real>& e) {
    const std::int32_t k = whole_exponent(e.shininess);
    return {e.colour, e.kd, e.ks, e.shininess, k, k, !specular_is_zero(e)};
}

// Ellipsoid e's ambient term Ka*Ia*O, as every hit on it computes it.
template <typename Real>
Vec3<Real> ambient_term(const Vec3<Real>& ambient_light, const Ellipsoid<Real>& e) {
    return (ambient_light * e.ka) * e.colour;
}

// Whether no light can add to e's colour: Kd = 0 and no specular term.
template <typename Real>
bool no_lighting(const Ellipsoid<Real>& e) {
    return specular_is_zero(e) && e.kd == 0;
}

// Whether a hit on e sends a mirrored ray: Kr > 0, and a bounce left of the
// kMaxReflections (spec_rules.h).
template <typename Real>
bool reflects(const Ellipsoid<Real>& e, int reflections_left) {
    return e.kr > 0 && reflections_left > 0;
}

// Whether e's colour is its ambient term alone wherever it is seen: no light nor mirror
// adds to it, so the fast paths know its pixels' bytes before any ray.
template <typename Real>
bool ambient_only(const Ellipsoid<Real>& e) {
    return no_lighting(e) && !(e.kr > 0);
}

// What shading knows of an ellipsoid before any ray, made once per scene.
template <typename Real>
struct SurfaceConstants {
    Vec3<Real> ambient_term;                     // ambient_term(): Ka * Ia * O
    bool no_lighting;                            // no_lighting(): no light adds anything
    bool ambient_only;                           // ambient_only(): the colour is the ambient term
    std::uint8_t ambient_bytes[kBytesPerPixel];  // pixel_bytes() of the ambient term
};
template <typename Real>
SurfaceConstants<Real> surface_constants(const Vec3<Real>& ambient_light, const Ellipsoid<Real>& e) {
    SurfaceConstants<Real> s{ambient_term(ambient_light, e), no_lighting(e), ambient_only(e), {}};
    pixel_bytes(s.ambient_term, s.ambient_bytes);
    return s;
}

// A ray's hit: the point, the unit normal facing the viewer, and normalize(-direction).
template <typename T>
struct SurfacePoint {
    Vec3<T> point, normal, to_viewer;
    T scaled_length;  // |(P - C) / s^2|, the normal's length: for the fast paths' culling
};

// The hit at origin + t direction on the ellipsoid of centre and scale^2; inside: the
// far root was taken, the ray sees the inner surface.
template <typename T>
RT_ALWAYS_INLINE SurfacePoint<T> surface_point(const Vec3<T>& origin, const Vec3<T>& direction, const T& t,
                                               MaskOf<T> inside, const Vec3<T>& centre,
                                               const Vec3<T>& scale_squared) {
    SurfacePoint<T> s;
    s.point = origin + direction * t;
    const Vec3<T> scaled = (s.point - centre) / scale_squared;
    s.scaled_length = length(scaled);
    const Vec3<T> outward = scaled * (T(1) / s.scaled_length);  // normalize()
    s.normal = select(inside, -outward, outward);               // seen from inside: face the viewer
    s.to_viewer = normalize(-direction);
    return s;
}

// The ray from a hit to a light (at t = 1), its unit direction L and N.L.
template <typename T>
struct LightRay {
    Vec3<T> to_light, l;
    T distance;  // |light - P|: for the fast paths' culling (exact_culling.h)
    T n_dot_l;
    MaskOf<T> faces;  // N.L > 0: a light behind the surface adds nothing, blocked or not
};

template <typename T>
RT_ALWAYS_INLINE LightRay<T> light_ray(const SurfacePoint<T>& s, const Vec3<T>& light) {
    LightRay<T> r;
    r.to_light = light - s.point;
    r.distance = length(r.to_light);
    r.l = r.to_light * (T(1) / r.distance);  // normalize()
    r.n_dot_l = dot(s.normal, r.l);
    r.faces = r.n_dot_l > T(0);
    return r;
}

// colour += the diffuse and specular terms of a light of this intensity, where it
// reaches the point (lit: it faces the surface and nothing blocks it).
template <typename T>
RT_ALWAYS_INLINE void add_light(Vec3<T>& colour, const SurfacePoint<T>& s, const LightRay<T>& r,
                                const Vec3<T>& intensity, const Finish<T>& f, MaskOf<T> lit) {
    colour = select(lit, colour + intensity * f.kd * r.n_dot_l * f.colour, colour);
    const MaskOf<T> may_shine = lit & f.specular;
    if (!any(may_shine)) return;
    const Vec3<T> reflected_light = s.normal * (T(2) * r.n_dot_l) - r.l;
    const T r_dot_v = dot(reflected_light, s.to_viewer);
    const MaskOf<T> shines = may_shine & (r_dot_v > T(0));
    if (!any(shines)) return;
    const T power = f.shared_exponent >= 0 ? whole_power(r_dot_v, f.shared_exponent)
                                           : specular_power(r_dot_v, f.shininess, f.exponent);
    colour = select(shines, colour + intensity * f.ks * power, colour);
}

// The direction a mirror of this unit normal sends a ray along direction.
template <typename T>
RT_ALWAYS_INLINE Vec3<T> mirrored(const Vec3<T>& normal, const Vec3<T>& direction) {
    return direction - normal * (T(2) * dot(normal, direction));
}

}  // namespace rt
