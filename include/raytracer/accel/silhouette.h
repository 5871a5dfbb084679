// Which rows of eye rays may meet an ellipsoid, and where in each: its silhouette from
// the camera, row by row. EyeBlock skips a row of a block that lies outside it (an
// ellipsoid near the camera covers far less of the screen than its box does:
// testImgPlane's sphere a quarter of it, its box all of it); the flat sweep narrows each
// row's columns to it (RowSpans, screen_bounds.h).
//
// The eye rays of the row at height y are d(x) = (x, y, near_z). Mapped into the unit
// space of the ellipsoid grown by kCullingGap of each scale (o' = -C / s', d' = d / s'),
// the line meets it where disc = (o'.d')^2 - |d'|^2 (|o'|^2 - 1) >= 0, a quadratic
// A u^2 + 2 B u + K in u = d'.x = x / s'.x: for an ellipsoid wholly in front of the eye,
// A < 0 and the row's rays that may meet it are one interval of u, between the roots. A
// ray that meets the ellipsoid itself lies deep inside that interval: the growth is 1e-3
// in the unit space, and where |o'| <= 1000 the rounding of the interval's ends is about
// 1e-10 of the same scale; a margin of two pixels' spacing is kept besides. Elsewhere
// (an ellipsoid that reaches the camera's plane or lies far away) no row is ruled out.
#pragma once

#include <cmath>
#include <limits>

#include "raytracer/accel/exact_culling.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/unit_sphere_roots.h"

namespace rt {

template <typename C>
class Silhouette {
public:
    template <typename Real>
    Silhouette(const Ellipsoid<Real>& e, C near_z) {
        using std::abs;
        const C grow = 1 + C(kCullingGap);
        const C sx = abs(C(e.scale.x)) * grow, sy = abs(C(e.scale.y)) * grow, sz = abs(C(e.scale.z)) * grow;
        sx_ = sx, ox_ = -C(e.centre.x) / sx, oy_ = -C(e.centre.y) / sy, oz_ = -C(e.centre.z) / sz;
        kx_ = 1 / sx, ky_ = 1 / sy, kz_ = 1 / sz;
        const C o2 = ox_ * ox_ + oy_ * oy_ + oz_ * oz_;
        gamma_ = o2 - 1;
        a_ = 1 - oy_ * oy_ - oz_ * oz_;
        dz_ = near_z * kz_;  // every row's d'.z
        z_long_ = abs(dz_) >= C(kLeastSquaredDirection);
        using std::isfinite;
        usable_ = C(e.centre.z) + sz < 0 && o2 <= C(1e6) && a_ < 0 && isfinite(kx_) && isfinite(ky_) &&
                  isfinite(kz_);
    }

    // The eye rays of the row at height y: false where none may meet the grown ellipsoid;
    // else [u_lo, u_hi], the interval of u = x / s'.x that holds those that may
    // (unbounded where no row is ruled out). The quadratic is taken in u, whose terms are
    // the unit space's (no square of a scale over- or underflows); where a term is not
    // finite, or the row's direction is below kLeastSquaredDirection there (both d'.y and
    // d'.z), no row is ruled out.
    bool row_span(C y, C& u_lo, C& u_hi) const {
        using std::abs;
        using std::isfinite;
        using std::sqrt;
        u_lo = -std::numeric_limits<C>::infinity(), u_hi = std::numeric_limits<C>::infinity();
        if (!usable_) return true;
        const C dy = y * ky_;  // d'.y
        if (!z_long_ && !(abs(dy) >= C(kLeastSquaredDirection))) return true;
        const C beta0 = oy_ * dy + oz_ * dz_;
        const C b = ox_ * beta0;
        const C k = beta0 * beta0 - (dy * dy + dz_ * dz_) * gamma_;
        const C disc = b * b - a_ * k;
        if (!isfinite(disc)) return true;
        if (!(disc >= 0)) return false;
        const C root = sqrt(disc);
        // a_ < 0: (-b + root) / a_ is the smaller root.
        const C lo = (-b + root) / a_, hi = (-b - root) / a_;
        if (isfinite(lo) && isfinite(hi)) u_lo = lo, u_hi = hi;
        return true;
    }
    // The x on the near plane of u.
    C x_of(C u) const { return u * sx_; }

    // Whether the eye rays of the row at height y with x in [x_lo, x_hi] may meet the
    // ellipsoid, margin (two pixels' spacing) allowed on both sides.
    bool row_may_meet(C y, C x_lo, C x_hi, C margin) const {
        C u_lo, u_hi;
        if (!row_span(y, u_lo, u_hi)) return false;
        const C from = (x_lo - margin) * kx_, to = (x_hi + margin) * kx_;
        using std::isfinite;
        if (!isfinite(from) || !isfinite(to)) return true;
        return u_hi >= from && u_lo <= to;
    }

private:
    C sx_, ox_, oy_, oz_, kx_, ky_, kz_, gamma_, a_, dz_;
    bool usable_, z_long_;
};

}  // namespace rt
