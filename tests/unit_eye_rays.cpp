// The eye rays intersected many columns at a time (eye_rays.h) against the scalar path
// they replace: intersect_mapped() per pixel and ellipsoid, and the nearest hit chosen
// as the reference's BruteForce::closest() does (visible_root(), spec_rules.h). Each column's ellipsoid, t
// (bit for bit) and inside flag must be equal, in double and long double (the flat sweep's precisions), with
// and without the column tables.
#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/flat_sweep/eye_rays.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"

namespace {

// Uniform in [lo, hi) from the raw generator output (the same numbers everywhere).
struct Frustum {
    double left, right, bottom, top, near_plane;
    int columns, rows;
};

// Ellipsoids of every awkward kind for eye rays: the camera on the surface (c = 0, and
// a grazing column where q = 0), cut by the near plane, thin, far, negative scales,
// enclosing the camera, behind it.
std::vector<rt::SphereSpec> awkward_ellipsoids(std::mt19937& g, int count) {
    std::vector<rt::SphereSpec> spheres;
    for (int i = 0; i < count; ++i) {
        rt::SphereSpec s{};
        s.scale = {uniform(g, 0.05, 3), uniform(g, 0.05, 3), uniform(g, 0.05, 3)};
        s.centre = {uniform(g, -4, 4), uniform(g, -4, 4), uniform(g, -12, -0.5)};
        switch (i % 7) {
            case 0:  // the camera on the surface, its normal along x: column x = 0 grazes it
                s.centre = {s.scale.x, 0, 0};
                break;
            case 1:  // cut by the near plane
                s.centre.z = -1;
                break;
            case 2:  // thin
                s.scale.z = 1e-4;
                break;
            case 3:  // far
                s.centre = {uniform(g, -1e4, 1e4), uniform(g, -1e4, 1e4), -1e5};
                s.scale = {500, 700, 300};
                break;
            case 4:  // negative scales
                s.scale = {-s.scale.x, s.scale.y, -s.scale.z};
                break;
            case 5:  // around the camera
                s.centre = {0.1, -0.2, 0.3};
                s.scale = {5, 4, 6};
                break;
            default:  // behind the camera
                s.centre.z = 5;
                break;
        }
        spheres.push_back(s);
    }
    return spheres;
}

template <typename Real>
struct Nearest {
    std::uint32_t ellipsoid = rt::kNoEllipsoid;
    Real t = 0;
    bool inside = false;
};

// The scalar reference: BruteForce::closest()'s choice over all ellipsoids with intersect_mapped().
template <typename Real>
Nearest<Real> reference(const std::vector<rt::Ellipsoid<Real>>& ellipsoids,
                        const std::vector<rt::MappedOrigin<Real>>& origins, const rt::Vec3<Real>& direction) {
    const Real min_t = rt::visible_beyond(Real(rt::kEyeRayMinT));
    Nearest<Real> best;
    for (std::uint32_t i = 0; i < ellipsoids.size(); ++i) {
        const rt::Roots<Real> r = rt::intersect_mapped(ellipsoids[i], origins[i], direction);
        if (!r.hit) continue;
        const bool inside = !(r.near > min_t);
        const Real t = inside ? r.far : r.near;
        if (t > min_t && (best.ellipsoid == rt::kNoEllipsoid || t < best.t)) best = {i, t, inside};
    }
    return best;
}

// Compares every pixel of rows_to_check rows; returns the number of differing pixels
// and counts the hits (so that a test of nothing cannot pass).
template <typename Real>
long long differing_pixels(const std::vector<rt::SphereSpec>& spheres, const Frustum& f, int rows_to_check,
                           long long& hits) {
    std::vector<rt::Ellipsoid<Real>> ellipsoids;
    std::vector<rt::MappedOrigin<Real>> origins;
    for (const rt::SphereSpec& s : spheres) {
        ellipsoids.push_back(rt::make_ellipsoid<Real>(s));
        origins.push_back(rt::mapped_origin(ellipsoids.back(), rt::Vec3<Real>{}));
    }
    // As every renderer computes them (spec_rules.h).
    const Real left = Real(f.left), right = Real(f.right), top = Real(f.top), bottom = Real(f.bottom);
    const Real near_z = -Real(f.near_plane);
    std::vector<Real> column_x(static_cast<std::size_t>(f.columns));
    for (int c = 0; c < f.columns; ++c)
        column_x[static_cast<std::size_t>(c)] = rt::pixel_x(left, right, c, f.columns);
    const std::vector<int> first(spheres.size(), 0), last(spheres.size(), f.columns - 1);
    const rt::EyeRays<Real> eye_rays(ellipsoids, origins, column_x, first, last);
    rt::EyeRowHits<Real> found(f.columns);

    long long differ = 0;
    for (int k = 0; k < rows_to_check; ++k) {
        const int r = k * (f.rows - 1) / std::max(1, rows_to_check - 1);
        const Real y = rt::pixel_y(top, bottom, r, f.rows);
        rt::EyeRays<Real>::clear(found, 0, f.columns - 1);
        for (std::uint32_t i = 0; i < spheres.size(); ++i)
            eye_rays.intersect(found, i, 0, f.columns - 1, column_x.data(), y, near_z);
        for (int c = 0; c < f.columns; ++c) {
            const auto at = static_cast<std::size_t>(c);
            const Nearest<Real> want =
                reference(ellipsoids, origins, rt::Vec3<Real>{column_x[at], y, near_z});
            const bool same = found.ellipsoid[at] == want.ellipsoid &&
                              (want.ellipsoid == rt::kNoEllipsoid ||
                               (found.t[at] == want.t && (found.inside[at] != 0) == want.inside));
            if (!same) ++differ;
            if (want.ellipsoid != rt::kNoEllipsoid) ++hits;
        }
    }
    return differ;
}

template <typename Real>
void check_random_scenes(int columns, int ellipsoids_per_scene, int scenes) {
    long long hits = 0, differ = 0;
    for (int seed = 1; seed <= scenes; ++seed) {
        std::mt19937 g(static_cast<unsigned>(seed));
        // Even columns and a symmetric screen: a column at exactly x = 0.
        const double half = uniform(g, 0.5, 1.5);
        const Frustum f{-half,   half, -uniform(g, 0.5, 1.5), uniform(g, 0.5, 1.5), uniform(g, 0.5, 2),
                        columns, 61};
        differ += differing_pixels<Real>(awkward_ellipsoids(g, ellipsoids_per_scene), f, 9, hits);
    }
    CHECK_EQ(differ, 0LL);
    CHECK(hits > 0);
}

}  // namespace

TEST(eye_rays_equal_the_scalar_path_in_double) { check_random_scenes<double>(128, 14, 20); }
TEST(eye_rays_equal_the_scalar_path_in_long_double) { check_random_scenes<long double>(128, 14, 20); }

// So many ellipsoids and columns that the later ones have no column table
// (computed per row instead): both ways must agree with the scalar path.
TEST(eye_rays_equal_the_scalar_path_without_column_tables) { check_random_scenes<double>(2048, 140, 1); }
