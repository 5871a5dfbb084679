// The recursive Whitted tracer of SPEC sections 3-5, a template on the scalar type so
// that the same code renders in float, double and long double.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "raytracer/ellipsoid.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

namespace rt {

// Epsilons and limits that the course keys fix (SPEC sections 3 and 5).
inline constexpr double kEyeRayMinT = 1.0;       // the near plane is at t = 1
inline constexpr double kShadowRayMinT = 0.001;  // the keys need 0.001, not 0.0001
inline constexpr double kReflectedRayMinT = 0.0001;
inline constexpr int kMaxReflections = 3;

template <typename Real>
struct PointLight {
    Vec3<Real> position;
    Vec3<Real> intensity;
};

template <typename Real>
class Tracer {
public:
    using V = Vec3<Real>;

    explicit Tracer(const Scene& scene)
        : ambient_(V::from(scene.ambient)), background_(V::from(scene.background)) {
        ellipsoids_.reserve(scene.spheres.size());
        for (const SphereSpec& s : scene.spheres) ellipsoids_.push_back(make_ellipsoid<Real>(s));
        lights_.reserve(scene.lights.size());
        for (const LightSpec& l : scene.lights)
            lights_.push_back({V::from(l.position), V::from(l.intensity)});
    }

    // The colour seen along an eye ray from the origin (the camera) in this direction.
    V trace_eye_ray(const V& direction) const {
        return trace(V{}, direction, Real(kEyeRayMinT), kMaxReflections, background_);
    }

    // The nearest surface along origin + t direction with t > min_t.
    struct Hit {
        const Ellipsoid<Real>* ellipsoid = nullptr;
        Real t = 0;
        bool inside = false;  // the far root was taken: the ray sees the inner surface
    };

    // A root computed within a few ulps of min_t cannot be told from one at min_t, and
    // one at min_t is not visible (the hit must lie beyond it). This decides the eye
    // rays through the rim where the near plane cuts an ellipsoid: keyIllum's pixels
    // (240,345), (360,345), (345,240), (345,360) have their far root at exactly t = 1
    // (a 3-4-5 triangle), which double rounding puts 2 ulps above 1. The ulps are those
    // of the scene's double numbers, whatever Real is (scene_precision.h), so
    // that long double decides these pixels as double does.
    Hit nearest_hit(const V& origin, const V& direction, Real min_t) const {
        min_t *= Real(1) + Real(8) * scene_epsilon<Real>();
        Hit best;
        for (const Ellipsoid<Real>& e : ellipsoids_) {
            const Roots<Real> r = intersect(e, origin, direction);
            if (!r.hit) continue;
            const bool inside = !(r.near > min_t);
            const Real t = inside ? r.far : r.near;
            if (t > min_t && (best.ellipsoid == nullptr || t < best.t)) best = {&e, t, inside};
        }
        return best;
    }

    // A light is blocked when any ellipsoid lies on the segment from the point to it.
    // The direction is light - point, not normalised, so the light is at t = 1.
    bool in_shadow(const V& point, const V& to_light) const {
        const Real min_t = Real(kShadowRayMinT);
        for (const Ellipsoid<Real>& e : ellipsoids_) {
            const Roots<Real> r = intersect(e, point, to_light);
            if (!r.hit) continue;
            if ((r.near > min_t && r.near < 1) || (r.far > min_t && r.far < 1)) return true;
        }
        return false;
    }

private:
    V trace(const V& origin, const V& direction, Real min_t, int reflections_left, const V& miss) const {
        const Hit hit = nearest_hit(origin, direction, min_t);
        if (hit.ellipsoid == nullptr) return miss;
        const Ellipsoid<Real>& e = *hit.ellipsoid;

        const V point = origin + direction * hit.t;
        V normal = outward_normal(e, point);
        if (hit.inside) normal = -normal;  // seen from inside: face the viewer
        const V to_viewer = normalize(-direction);

        // The terms are multiplied in the order the handout writes them: Ka*Ia*O, Kd*Ip*(N.L)*O
        // and Ks*Ip*(R.V)^n; a different order moves a few pixels across a truncation step.
        V colour = (ambient_ * e.ka) * e.colour;
        for (const PointLight<Real>& light : lights_) {
            const V to_light = light.position - point;
            if (in_shadow(point, to_light)) continue;
            const V l = normalize(to_light);
            const Real n_dot_l = dot(normal, l);
            if (!(n_dot_l > 0)) continue;
            colour += ((light.intensity * e.kd) * n_dot_l) * e.colour;
            const V reflected_light = normal * (2 * n_dot_l) - l;
            const Real r_dot_v = dot(reflected_light, to_viewer);
            if (r_dot_v > 0) {
                using std::pow;
                colour += (light.intensity * e.ks) * pow(r_dot_v, e.shininess);
            }
        }

        if (e.kr > 0 && reflections_left > 0) {
            const V mirrored = direction - normal * (2 * dot(normal, direction));
            // A reflected ray that hits nothing returns black, unlike an eye ray.
            colour += trace(point, mirrored, Real(kReflectedRayMinT), reflections_left - 1, V{}) * e.kr;
        }
        return colour;
    }

    std::vector<Ellipsoid<Real>> ellipsoids_;
    std::vector<PointLight<Real>> lights_;
    V ambient_;
    V background_;
};

}  // namespace rt
