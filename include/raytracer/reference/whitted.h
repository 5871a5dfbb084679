// The reference path of SPEC sections 3-5, in plain scalar code: a pixel's eye ray, the
// nearest surface it meets, its Phong shading with hard shadows, up to three mirror
// bounces, and the pixel's bytes. Geometry answers the two queries (closest hit, any
// hit): BruteForce (brute_force.h) tries every ellipsoid, Bvh (bvh.h) prunes with a
// tree, and both give the same answers, so the same bytes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/image.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/power.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/scene.h"
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

    // trace(): the colour seen along origin + t direction beyond min_t; miss when
    // nothing is hit (BACK for eye rays, black for reflected rays).
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
        const Surface s = surface(hit, origin, direction, reflections_left);
        V colour = s.material->ambient;
        for (std::size_t li = 0; li < lights_.size() && !s.material->no_lighting; ++li) {
            const LightRay r = light_ray(s, li);
            // A light behind the surface adds nothing, blocked or not.
            if (r.faces && !geometry_.occluded(s.point, r.to_light, scratch.blockers[li]))
                add_light(colour, s, li, r);
        }
        if (s.reflects)
            colour += trace(s.point, mirrored(s, direction), kReflectedRayMinT, reflections_left - 1, V{},
                            scratch) *
                      s.ellipsoid->kr;
        return colour;
    }

    // The pieces of shade(), for a driver that shades many hits at once (whitted_tiles.h).
    struct Material {
        V ambient;              // Ka * Ia * O
        bool no_specular;       // Ks = 0 (and pow finite)
        bool no_lighting;       // Kd = Ks = 0
        std::int32_t exponent;  // whole_exponent(n): -1 when pow() is needed
    };
    struct Surface {
        const Ellipsoid<Real>* ellipsoid;
        const Material* material;
        V point, normal, to_viewer;  // the normal faces the viewer
        bool reflects;               // a reflected ray is traced
    };
    Surface surface(const NearestHit<Real>& hit, const V& origin, const V& direction,
                    int reflections_left) const {
        Surface s;
        s.ellipsoid = &geometry_.ellipsoid(hit.ellipsoid);
        s.material = &materials_[hit.ellipsoid];
        s.point = origin + direction * hit.t;
        s.normal = normalize((s.point - s.ellipsoid->centre) / s.ellipsoid->scale_squared);
        if (hit.inside) s.normal = -s.normal;  // seen from inside: face the viewer
        s.to_viewer = normalize(-direction);
        s.reflects = s.ellipsoid->kr > 0 && reflections_left > 0;
        return s;
    }
    struct LightRay {
        V to_light;  // the light at t = 1
        V l;         // unit
        Real n_dot_l;
        bool faces;  // N.L > 0
    };
    LightRay light_ray(const Surface& s, std::size_t li) const {
        LightRay r;
        r.to_light = lights_[li].position - s.point;
        r.l = normalize(r.to_light);
        r.n_dot_l = dot(s.normal, r.l);
        r.faces = r.n_dot_l > 0;
        return r;
    }
    // The diffuse and specular terms of an unblocked light.
    void add_light(V& colour, const Surface& s, std::size_t li, const LightRay& r) const {
        const Light& light = lights_[li];
        const Ellipsoid<Real>& e = *s.ellipsoid;
        colour += light.intensity * e.kd * r.n_dot_l * e.colour;
        if (s.material->no_specular) return;
        const V reflected_light = s.normal * (2 * r.n_dot_l) - r.l;
        const Real r_dot_v = dot(reflected_light, s.to_viewer);
        if (r_dot_v > 0)
            colour += light.intensity * e.ks * specular_power(r_dot_v, e.shininess, s.material->exponent);
    }
    static V mirrored(const Surface& s, const V& direction) {
        return direction - s.normal * (2 * dot(s.normal, direction));
    }
    std::size_t light_count() const { return lights_.size(); }
    const V& light_position(std::size_t li) const { return lights_[li].position; }
    const Geometry& geometry() const { return geometry_; }
    const V& background() const { return background_; }
    Real near_z() const { return near_z_; }

private:
    struct Light {
        V position, intensity;
    };

    Geometry geometry_;  // holds the ellipsoids
    std::vector<Light> lights_;
    std::vector<Material> materials_;  // per ellipsoid
    V ambient_, background_;
    Real left_, right_, bottom_, top_, near_z_, columns_, rows_;
};

}  // namespace rt
