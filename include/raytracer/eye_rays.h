// The eye rays of one row against one ellipsoid, for a whole run of columns at once,
// and the nearest hit per column over the row's ellipsoids.
//
// WHY: per pixel and candidate ellipsoid, intersect_mapped() is a few dozen scalar
// operations and four divisions, with the candidates found by scanning the row's spans
// per pixel. Here each (row, ellipsoid) pair is one plain loop over its columns with
// the values in arrays (structure of arrays, no branches), which GCC vectorises: the
// same IEEE operations in vector lanes give the same bits as the scalar code (the build
// uses -ffp-contract=off, so nothing is fused). Measured in docs/speed.md.
//
// Bit-identity: the loop is intersect_mapped() operation for operation, in the same
// order (d = direction / s, a = d.d, b = o'.d, l = o' - d (b/a), the tangent rule,
// q = -(b + copysign(sqrt(a (1 - l.l)), b)), the q == 0 case, the swap), and the merge
// is Tracer::closest(): ellipsoids in increasing order, inside = !(near > min_t),
// t = inside ? far : near, accepted when t > min_t and (no hit yet or t < best t).
// Terms that depend only on the row or the ellipsoid (y / s.y, (y / s.y)^2, o'.y y / s.y,
// ...) are computed once per row: the same operations on the same values.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/ellipsoid.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// Per column of the image (one per thread): the nearest hit found so far in the row.
template <typename Real>
struct EyeRowHits {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFU;
    std::vector<Real> t;                   // NaN until a hit is accepted
    std::vector<std::uint32_t> ellipsoid;  // kNone until a hit is accepted
    // The far root was taken (0 or 1). As wide as the index: with mixed widths GCC's
    // vector code packs and unpacks the lanes (2.5 % more instructions on the course scenes).
    std::vector<std::uint32_t> inside;

    explicit EyeRowHits(int columns)
        : t(static_cast<std::size_t>(columns)),
          ellipsoid(static_cast<std::size_t>(columns)),
          inside(static_cast<std::size_t>(columns)) {}
};

template <typename Real>
class EyeRays {
public:
    // ellipsoids[i] and origins[i] (mapped_origin() of the camera) for every ellipsoid;
    // min_t as Tracer::eye_min_t(); column_x[c] the x of column c's eye ray; columns
    // [first_column[i], last_column[i]] the only ones ever asked of ellipsoid i.
    EyeRays(const std::vector<Ellipsoid<Real>>& ellipsoids, const std::vector<MappedOrigin<Real>>& origins,
            Real min_t, const std::vector<Real>& column_x, const std::vector<int>& first_column,
            const std::vector<int>& last_column)
        : min_t_(min_t) {
        terms_.reserve(ellipsoids.size());
        std::size_t table_size = 0;
        for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
            using std::abs;
            const Vec3<Real>& o = origins[i].o;
            const Real distance = std::max(abs(o.x), std::max(abs(o.y), abs(o.z)));
            Terms terms{ellipsoids[i].scale, o,
                        origins[i].c,        -Real(4) * scene_epsilon<Real>() * (Real(1) + distance),
                        first_column[i],     0};
            // The column terms d.x = x / s.x, d.x^2 and o'.x d.x per ellipsoid and column,
            // unless the tables would grow large (then they are computed per row).
            const std::size_t width =
                first_column[i] <= last_column[i] ? std::size_t(last_column[i] - first_column[i] + 1) : 0;
            terms.table = table_size + width <= kMaxTable ? table_size : kNoTable;
            if (terms.table != kNoTable) {
                table_size += width;
                for (int c = first_column[i]; c <= last_column[i]; ++c) {
                    const Real dx = column_x[static_cast<std::size_t>(c)] / terms.scale.x;
                    dx_.push_back(dx);
                    dx_dx_.push_back(dx * dx);
                    ox_dx_.push_back(o.x * dx);
                }
            }
            terms_.push_back(terms);
        }
    }

    // Forgets the hits of columns [first, last].
    static void clear(EyeRowHits<Real>& hits, int first, int last) {
        for (int c = first; c <= last; ++c) {
            hits.t[static_cast<std::size_t>(c)] = std::numeric_limits<Real>::quiet_NaN();
            hits.ellipsoid[static_cast<std::size_t>(c)] = EyeRowHits<Real>::kNone;
        }
    }

    // Intersects the eye rays (column_x[c], y, near_z) of columns [first, last] with
    // ellipsoid i and keeps each column's nearest hit. Called for a row's ellipsoids in
    // increasing order, as Tracer::closest() tries them.
    void intersect(EyeRowHits<Real>& hits, std::uint32_t i, int first, int last, const Real* column_x, Real y,
                   Real near_z) const {
        const Terms& e = terms_[i];
        if (e.table != kNoTable) {
            const std::ptrdiff_t at = std::ptrdiff_t(e.table) - e.first_column;
            const Real* const dx = dx_.data() + at;
            const Real* const dx_dx = dx_dx_.data() + at;
            const Real* const ox_dx = ox_dx_.data() + at;
            intersect(hits, i, first, last, y, near_z,
                      [&](int c, Real& x, Real& xx, Real& ox) { x = dx[c], xx = dx_dx[c], ox = ox_dx[c]; });
        } else {
            const Real sx = e.scale.x, o_x = e.o.x;
            intersect(hits, i, first, last, y, near_z, [&](int c, Real& x, Real& xx, Real& ox) {
                x = column_x[c] / sx, xx = x * x, ox = o_x * x;
            });
        }
    }

private:
    // The loop itself; column_terms(c, dx, dx_dx, ox_dx) gives d.x = x / s.x, d.x^2 and
    // o'.x d.x of column c.
    template <typename ColumnTerms>
    void intersect(EyeRowHits<Real>& hits, std::uint32_t i, int first, int last, Real y, Real near_z,
                   ColumnTerms column_terms) const {
        using std::sqrt;
        const Terms& e = terms_[i];
        // The row's and the ellipsoid's parts of d = direction / s, d.d and o'.d.
        const Real dy = y / e.scale.y, dz = near_z / e.scale.z;
        const Real dy_dy = dy * dy, dz_dz = dz * dz;
        const Real oy_dy = e.o.y * dy, oz_dz = e.o.z * dz;
        const Real ox = e.o.x, oy = e.o.y, oz = e.o.z, c_term = e.c;
        const Real tangent = e.tangent, min_t = min_t_;
        Real* const best_t = hits.t.data();
        std::uint32_t* const best = hits.ellipsoid.data();
        std::uint32_t* const best_inside = hits.inside.data();
        for (int c = first; c <= last; ++c) {
            Real dx, dx_dx, ox_dx;
            column_terms(c, dx, dx_dx, ox_dx);
            const Real a = dx_dx + dy_dy + dz_dz;
            const Real b = ox_dx + oy_dy + oz_dz;
            const Real k = b / a;
            const Real lx = ox - dx * k, ly = oy - dy * k, lz = oz - dz * k;
            Real unit_disc = Real(1) - (lx * lx + ly * ly + lz * lz);
            const bool miss = unit_disc < tangent;  // tangent < 0: only when unit_disc < 0
            unit_disc = unit_disc < 0 ? Real(0) : unit_disc;
            const Real root = sqrt(a * unit_disc);
            const Real q = -(b + std::copysign(root, b));
            const Real t1 = q / a, t2 = c_term / q;
            Real near = t1 > t2 ? t2 : t1, far = t1 > t2 ? t1 : t2;
            near = q == 0 ? Real(0) : near;
            far = q == 0 ? Real(0) : far;
            // Tracer::closest(); a NaN best t (no hit yet) makes !(t >= best t) true, and an
            // accepted t is never NaN, so that test is t < best t otherwise.
            const bool inside = !(near > min_t);
            const Real t = inside ? far : near;
            const bool accept = !miss && t > min_t && !(t >= best_t[c]);
            best_t[c] = accept ? t : best_t[c];
            best[c] = accept ? i : best[c];
            best_inside[c] = accept ? std::uint32_t(inside) : best_inside[c];
        }
    }

    static constexpr std::size_t kMaxTable = std::size_t(1) << 18;  // entries: 3 x 2 MiB in double
    static constexpr std::size_t kNoTable = ~std::size_t(0);
    struct Terms {
        Vec3<Real> scale, o;  // s and o' = (camera - C) / s
        Real c;               // o'.o' - 1
        Real tangent;         // intersect_mapped()'s tangent limit on 1 - l.l
        int first_column;     // of the tables
        std::size_t table;    // where its columns start in the tables, or kNoTable
    };
    std::vector<Terms> terms_;
    std::vector<Real> dx_, dx_dx_, ox_dx_;  // per ellipsoid and column, see the constructor
    Real min_t_;
};

}  // namespace rt
