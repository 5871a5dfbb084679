// For each ellipsoid, a rectangle of pixels outside which no eye ray can meet it.
//
// WHY: on the course scenes most pixels see only the background, and at 400x400 the
// whole render must cost about as much as starting a process; a per-pixel test of
// every ellipsoid (or a direction-grid lookup) was most of the time. With these
// rectangles a row's candidate ellipsoids are known before its pixels, and a pixel
// none covers is the background without tracing.
//
// The rectangle bounds the projection of the ellipsoid's inflated bounding sphere
// (sphere_bounds.h) on the near plane: the planes through the eye tangent to the
// sphere, x + m z = 0, satisfy (Cz^2 - R^2) m^2 + 2 Cx Cz m + Cx^2 - R^2 = 0, and cut
// the near plane z = -near at x = m near (likewise for y). Two pixels of margin on each
// side absorb every rounding of the pixel positions; a sphere that reaches the plane
// z = 0 (or is too far for the rounding argument) gets the whole screen.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "raytracer/accel/silhouette.h"
#include "raytracer/flat_sweep/bounding_sphere.h"
#include "raytracer/reference/unit_sphere_roots.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

namespace rt {

struct PixelRect {
    int first_column, last_column, first_row, last_row;  // inclusive; empty when first > last
};

// spheres[i] bounds ellipsoid i; culls_eye_rays[i] says whether the rounding argument
// holds for rays from the eye (else the whole screen is kept).
template <typename C>
std::vector<PixelRect> screen_bounds(const Scene& scene, const std::vector<BoundingSphere<C>>& spheres,
                                     const std::vector<bool>& culls_eye_rays) {
    const PixelRect whole{0, scene.columns - 1, 0, scene.rows - 1};
    std::vector<PixelRect> rects;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        const BoundingSphere<C>& s = spheres[i];
        if (!culls_eye_rays[i]) {
            rects.push_back(whole);
            continue;
        }
        if (s.z - s.radius > 0) {  // wholly behind the eye: no eye ray meets it at t > 0
            rects.push_back({0, -1, 0, -1});
            continue;
        }
        if (!(s.z + s.radius < 0)) {  // reaches z = 0: no bounded projection
            rects.push_back(whole);
            continue;
        }
        // The range of m over the tangent planes x + m z = 0 (or y + m z = 0).
        auto range = [&](C centre, C& lo, C& hi) {
            using std::sqrt;
            const C a = s.z * s.z - s.radius * s.radius, b = centre * s.z;
            const C c = centre * centre - s.radius * s.radius;
            const C root = sqrt(std::max(C(0), b * b - a * c));
            lo = (-b - root) / a, hi = (-b + root) / a;
            if (lo > hi) std::swap(lo, hi);
        };
        C mx_lo, mx_hi, my_lo, my_hi;
        range(s.x, mx_lo, mx_hi);
        range(s.y, my_lo, my_hi);
        const C near_plane = C(scene.near_plane);
        // Pixel column c looks through x = left + (right - left) c / columns, row r through
        // y = top - (top - bottom) r / rows.
        const C column_scale = C(scene.columns) / (C(scene.right) - C(scene.left));
        const C row_scale = C(scene.rows) / (C(scene.top) - C(scene.bottom));
        const C c_lo = (mx_lo * near_plane - C(scene.left)) * column_scale;
        const C c_hi = (mx_hi * near_plane - C(scene.left)) * column_scale;
        const C r_lo = (C(scene.top) - my_hi * near_plane) * row_scale;
        const C r_hi = (C(scene.top) - my_lo * near_plane) * row_scale;
        auto clamp_index = [](C v, int size) {
            using std::floor;
            if (!(v > -2)) return -2;  // also NaN: handled by the check below
            if (v > C(size) + 2) return size + 2;
            return static_cast<int>(floor(v));
        };
        PixelRect r{std::max(0, clamp_index(c_lo, scene.columns) - 2),
                    std::min(scene.columns - 1, clamp_index(c_hi, scene.columns) + 2),
                    std::max(0, clamp_index(r_lo, scene.rows) - 2),
                    std::min(scene.rows - 1, clamp_index(r_hi, scene.rows) + 2)};
        const bool finite = c_lo == c_lo && c_hi == c_hi && r_lo == r_lo && r_hi == r_hi;
        rects.push_back(finite ? r : whole);
    }
    return rects;
}

// Tighter than the rectangle: within one row, the columns whose eye rays may meet an
// ellipsoid: its silhouette's span of the row (silhouette.h), two columns of margin on
// each side, as for the rectangle. Only for an ellipsoid whose guard holds the camera
// (culls_eye_rays); otherwise the rectangle's columns stand.
template <typename C>
class RowSpans {
public:
    RowSpans() = default;

    template <typename Real>
    RowSpans(const Scene& scene, const std::vector<Ellipsoid<Real>>& ellipsoids,
             std::vector<bool> culls_eye_rays)
        : culls_eye_rays_(std::move(culls_eye_rays)),
          left_(C(scene.left)),
          column_scale_(C(scene.columns) / (C(scene.right) - C(scene.left))),
          columns_(scene.columns) {
        for (const Ellipsoid<Real>& e : ellipsoids) silhouettes_.emplace_back(e, -C(scene.near_plane));
    }

    // Narrows [first, last] to the columns of the row at height y that may see
    // ellipsoid i; false when none may.
    bool narrow(std::size_t i, C y, int& first, int& last) const {
        C u_lo, u_hi;
        if (!culls_eye_rays_[i]) return first <= last;
        if (!silhouettes_[i].row_span(y, u_lo, u_hi)) return false;
        const C c_lo = (silhouettes_[i].x_of(u_lo) - left_) * column_scale_;
        const C c_hi = (silhouettes_[i].x_of(u_hi) - left_) * column_scale_;
        if (c_lo != c_lo || c_hi != c_hi) return first <= last;  // NaN: nothing ruled out
        if (!(c_hi > -3) || !(c_lo < C(columns_) + 3)) return false;
        using std::floor;
        if (c_lo > C(first) + 2) first = static_cast<int>(floor(c_lo)) - 2;
        if (c_hi < C(last) - 2) last = static_cast<int>(floor(c_hi)) + 2;
        return first <= last;
    }

private:
    std::vector<Silhouette<C>> silhouettes_;
    std::vector<bool> culls_eye_rays_;
    C left_ = 0, column_scale_ = 1;
    int columns_ = 0;
};

}  // namespace rt
