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
#include "raytracer/large_pages.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/shading.h"
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
          lights_(point_lights<Real>(scene)),
          background_(V::from(scene.background)),
          left_(Real(scene.left)),
          right_(Real(scene.right)),
          bottom_(Real(scene.bottom)),
          top_(Real(scene.top)),
          near_z_(-Real(scene.near_plane)),
          columns_(scene.columns),
          rows_(scene.rows) {
        const V ambient_light = V::from(scene.ambient);
        surfaces_.reserve(scene.spheres.size());
        for (std::uint32_t i = 0; i < scene.spheres.size(); ++i)
            surfaces_.push_back(surface_constants(ambient_light, geometry_.ellipsoid(i)));
    }

    // The x of column c and the y of row r on the near plane (spec_rules.h).
    Real column_x(int c) const { return pixel_x(left_, right_, c, columns_); }
    Real row_y(int r) const { return pixel_y(top_, bottom_, r, rows_); }

    // A thread's working memory, this path's one aid to speed: per light, the ellipsoid its
    // last shadow ray was blocked by, which the geometry tries first for the next (its
    // occluded()): neighbouring pixels are mostly blocked by the same one. It never changes
    // an answer. Each geometry numbers it its own way (BruteForce by scene index, Bvh by
    // position in leaf order). The tree's tiles keep theirs per ellipsoid and light
    // instead (blocker_hints.h).
    struct Scratch {
        std::vector<std::uint32_t> blocker_hints;
    };
    Scratch make_scratch() const { return {std::vector<std::uint32_t>(lights_.size(), kNoEllipsoid)}; }

    // The three bytes of the pixel of column c and row r (pixel_bytes(): image.h, SPEC
    // section 6), whose eye ray goes from the camera through (column_x(c), row_y(r)); and
    // of an eye ray through any (x, y) on the near plane.
    void pixel(int c, int r, std::uint8_t* out, Scratch& scratch) const {
        pixel_through(column_x(c), row_y(r), out, scratch);
    }
    void pixel_through(Real x, Real y, std::uint8_t* out, Scratch& scratch) const {
        pixel_bytes(eye_ray_colour({x, y, near_z_}, scratch), out);
    }
    // The colour seen from the camera along direction (before conversion to bytes).
    V eye_ray_colour(const V& direction, Scratch& scratch) const {
        const V camera{};  // at the origin (SPEC section 3)
        return trace(camera, direction, kEyeRayMinT, kMaxReflections, background_, scratch);
    }

    // trace(): the colour seen along origin + t direction beyond min_t; miss when
    // nothing is hit (BACK for eye rays, black for reflected rays).
    V trace(const V& origin, const V& direction, double min_t, int reflections_left, const V& miss,
            Scratch& scratch) const {
        const NearestHit<Real> hit = geometry_.closest(origin, direction, min_t);
        return hit.found() ? shade(hit, origin, direction, reflections_left, scratch) : miss;
    }

    // The colour of the surface hit by origin + t direction (shading.h).
    V shade(const NearestHit<Real>& hit, const V& origin, const V& direction, int reflections_left,
            Scratch& scratch) const {
        const Ellipsoid<Real>& e = geometry_.ellipsoid(hit.ellipsoid);
        const SurfaceConstants<Real>& surface = surfaces_[hit.ellipsoid];
        const SurfacePoint<Real> s =
            surface_point(origin, direction, hit.t, hit.inside, e.centre, e.scale_squared);
        V colour = surface.ambient_term;
        const Finish<Real> finish = finish_of(e);
        for (std::size_t li = 0; li < lights_.size() && !surface.no_lighting; ++li) {
            const LightRay<Real> r = light_ray(s, lights_[li].position);
            if (r.faces && !geometry_.occluded(s.point, r.to_light, scratch.blocker_hints[li]))
                add_light(colour, s, r, lights_[li].intensity, finish, /*lit=*/true);
        }
        if (reflects(e, reflections_left))
            colour += trace(s.point, mirrored(s.normal, direction), kReflectedRayMinT, reflections_left - 1,
                            /*miss=*/V{}, scratch) *
                      e.kr;
        return colour;
    }

    // For the tree's tiles, which shade many hits at once (whitted_tiles.h).
    const SurfaceConstants<Real>& surface(std::uint32_t i) const { return surfaces_[i]; }
    std::size_t ellipsoid_count() const { return surfaces_.size(); }
    const std::vector<PointLight<Real>>& lights() const { return lights_; }
    std::size_t light_count() const { return lights_.size(); }
    const V& light_position(std::size_t li) const { return lights_[li].position; }
    const V& light_intensity(std::size_t li) const { return lights_[li].intensity; }
    const Geometry& geometry() const { return geometry_; }
    const V& background() const { return background_; }
    Real near_z() const { return near_z_; }

private:
    Geometry geometry_;  // holds the ellipsoids
    std::vector<PointLight<Real>> lights_;
    LargeVector<SurfaceConstants<Real>> surfaces_;  // per ellipsoid
    V background_;
    Real left_, right_, bottom_, top_, near_z_;
    int columns_, rows_;
};

}  // namespace rt
