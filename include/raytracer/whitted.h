// The reference path of SPEC sections 3-5, in plain scalar code: a pixel's eye ray, the
// nearest surface it meets, its Phong shading with hard shadows, up to three mirror
// bounces, and the pixel's bytes. Geometry answers the two queries (closest hit, any
// hit): BruteForce (brute_force.h) tries every ellipsoid, Bvh (bvh.h) prunes with a
// tree, and both give the same answers, so the same bytes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/ellipsoid.h"
#include "raytracer/image.h"
#include "raytracer/power.h"
#include "raytracer/scene.h"
#include "raytracer/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename Real, typename Geometry>
class Whitted {
public:
    using V = Vec3<Real>;

    // geometry: over make_ellipsoids<Real>(scene).
    Whitted(const Scene& scene, Geometry geometry)
        : geometry_(std::move(geometry)),
          ambient_(V::from(scene.ambient)),
          background_(V::from(scene.background)),
          left_(Real(scene.left)),
          right_(Real(scene.right)),
          bottom_(Real(scene.bottom)),
          top_(Real(scene.top)),
          near_z_(-Real(scene.near_plane)),
          columns_(Real(scene.columns)),
          rows_(Real(scene.rows)) {
        for (const LightSpec& l : scene.lights)
            lights_.push_back({V::from(l.position), V::from(l.intensity)});
        for (std::uint32_t i = 0; i < scene.spheres.size(); ++i) {
            const Ellipsoid<Real>& e = geometry_.ellipsoid(i);
            const bool no_specular = specular_is_zero(e);  // with Kd = 0 too, no light adds anything
            materials_.push_back({(ambient_ * e.ka) * e.colour, no_specular, no_specular && e.kd == 0,
                                  whole_exponent(e.shininess)});
        }
    }

    // The x of column c and the y of row r on the near plane: the pixel's top-left
    // corner, not its centre (the keys demand it; SPEC section 3).
    Real column_x(int c) const { return left_ + (right_ - left_) * Real(c) / columns_; }
    Real row_y(int r) const { return top_ - (top_ - bottom_) * Real(r) / rows_; }

    // A thread's working memory: per light, the geometry's hint for its shadow rays
    // (spec_rules.h). Neighbouring pixels share their shadows.
    struct Scratch {
        std::vector<std::uint32_t> blockers;
    };
    Scratch make_scratch() const { return {std::vector<std::uint32_t>(lights_.size(), kNoBlocker)}; }

    // The three bytes of the pixel whose eye ray goes from the camera through (x, y).
    void pixel(Real x, Real y, std::uint8_t* out, Scratch& scratch) const {
        const V colour = trace({}, {x, y, near_z_}, kEyeRayMinT, kMaxReflections, background_, scratch);
        out[0] = to_byte(colour.x), out[1] = to_byte(colour.y), out[2] = to_byte(colour.z);
    }

private:
    struct Light {
        V position, intensity;
    };
    struct Material {
        V ambient;              // Ka * Ia * O
        bool no_specular;       // Ks = 0 (and pow finite)
        bool no_lighting;       // Kd = Ks = 0
        std::int32_t exponent;  // whole_exponent(n): -1 when pow() is needed
    };

    // The colour seen along origin + t direction beyond min_t; miss when nothing is hit
    // (BACK for eye rays, black for reflected rays).
    V trace(const V& origin, const V& direction, double min_t, int reflections_left, const V& miss,
            Scratch& scratch) const {
        const NearestHit<Real> hit = geometry_.closest(origin, direction, min_t);
        return hit.found() ? shade(hit, origin, direction, reflections_left, scratch) : miss;
    }

    // The colour of the surface hit by origin + t direction. The terms are multiplied in
    // the order the handout writes them: Ka*Ia*O, Kd*Ip*(N.L)*O and Ks*Ip*(R.V)^n; a
    // different order moves a few pixels across a truncation step. A term that is
    // exactly zero is skipped (adding it changes at most the sign of a zero channel).
    V shade(const NearestHit<Real>& hit, const V& origin, const V& direction, int reflections_left,
            Scratch& scratch) const {
        const Ellipsoid<Real>& e = geometry_.ellipsoid(hit.ellipsoid);
        const Material& m = materials_[hit.ellipsoid];
        V colour = m.ambient;
        const bool reflects = e.kr > 0 && reflections_left > 0;
        if (m.no_lighting && !reflects) return colour;

        const V point = origin + direction * hit.t;
        V normal = normalize((point - e.centre) / e.scale_squared);
        if (hit.inside) normal = -normal;  // seen from inside: face the viewer
        const V to_viewer = normalize(-direction);
        for (std::size_t li = 0; li < lights_.size() && !m.no_lighting; ++li) {
            const Light& light = lights_[li];
            const V to_light = light.position - point;  // the light at t = 1
            const V l = normalize(to_light);
            const Real n_dot_l = dot(normal, l);
            // A light behind the surface adds nothing, blocked or not.
            if (!(n_dot_l > 0) || geometry_.occluded(point, to_light, scratch.blockers[li])) continue;
            colour += light.intensity * e.kd * n_dot_l * e.colour;
            if (m.no_specular) continue;
            const V reflected_light = normal * (2 * n_dot_l) - l;
            const Real r_dot_v = dot(reflected_light, to_viewer);
            if (r_dot_v > 0)
                colour += light.intensity * e.ks * specular_power(r_dot_v, e.shininess, m.exponent);
        }
        if (reflects) {
            const V mirrored = direction - normal * (2 * dot(normal, direction));
            colour += trace(point, mirrored, kReflectedRayMinT, reflections_left - 1, V{}, scratch) * e.kr;
        }
        return colour;
    }

    Geometry geometry_;  // holds the ellipsoids
    std::vector<Light> lights_;
    std::vector<Material> materials_;  // per ellipsoid
    V ambient_, background_;
    Real left_, right_, bottom_, top_, near_z_, columns_, rows_;
};

}  // namespace rt
