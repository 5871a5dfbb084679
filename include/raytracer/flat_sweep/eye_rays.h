// The eye rays of one row against one ellipsoid, for a whole run of columns at once,
// and the nearest hit per column over the row's ellipsoids.
//
// WHY: per pixel and candidate ellipsoid, intersect_mapped() is a few dozen scalar
// operations and four divisions, with the candidates found by scanning the row's spans
// per pixel. Here each (row, ellipsoid) pair is two plain loops over its columns with
// the values in arrays (structure of arrays, no branches), which GCC vectorises: the
// same IEEE operations in vector lanes give the same bits as the scalar code (the build
// uses -ffp-contract=off, so nothing is fused). Measured in docs/speed.md.
//
// Bit-identity: the loop runs the one root solver, unit_sphere_roots(), on the inputs
// intersect_mapped() gives it (o' and c of mapped_origin(), d' = direction / s), and the
// merge is the reference's (BruteForce::closest(), visible_root()): ellipsoids in
// increasing order, inside = !(near > min_t),
// t = inside ? far : near, accepted when t > min_t and (no hit yet or t < best t).
// d'.y = y / s.y and d'.z = near_z / s.z are computed once per row, d'.x = x / s.x once
// per column: the same operations on the same values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/compiler.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/unit_sphere_roots.h"
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
            Terms terms{ellipsoids[i].scale, origins[i].o, origins[i].c, first_column[i], 0};
            // The column terms d'.x = x / s.x per ellipsoid and column, unless the table
            // would grow large (then they are computed per row).
            const std::size_t width =
                first_column[i] <= last_column[i] ? std::size_t(last_column[i] - first_column[i] + 1) : 0;
            terms.table = table_size + width <= kMaxTable ? table_size : kNoTable;
            if (terms.table != kNoTable) {
                table_size += width;
                for (int c = first_column[i]; c <= last_column[i]; ++c)
                    dx_.push_back(column_x[static_cast<std::size_t>(c)] / terms.scale.x);
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
    // increasing order, as BruteForce::closest() tries them.
    void intersect(EyeRowHits<Real>& hits, std::uint32_t i, int first, int last, const Real* column_x, Real y,
                   Real near_z) const {
        const Terms& e = terms_[i];
        if (e.table != kNoTable) {
            const Real* const dx = dx_.data() + (std::ptrdiff_t(e.table) - e.first_column);
            intersect(hits, i, first, last, y, near_z, [&](int c) { return dx[c]; });
        } else {
            const Real sx = e.scale.x;
            intersect(hits, i, first, last, y, near_z, [&](int c) { return column_x[c] / sx; });
        }
    }

private:
    // The loop itself; column_dx(c) gives d'.x = x / s.x of column c.
    template <typename ColumnDx>
    void intersect(EyeRowHits<Real>& hits, std::uint32_t i, int first, int last, Real y, Real near_z,
                   ColumnDx column_dx) const {
        const Terms& e = terms_[i];
        const Real dy = y / e.scale.y, dz = near_z / e.scale.z;  // the row's part of d'
        const Real ox = e.o.x, oy = e.o.y, oz = e.o.z, c_term = e.c, min_t = min_t_;
        Real* const best_t = hits.t.data();
        std::uint32_t* const best = hits.ellipsoid.data();
        std::uint32_t* const best_inside = hits.inside.data();
        // The roots of a block of columns first, then their merge. WHY: GCC 12 keeps a
        // loop that does both scalar (it folds the solver's hit into a select of
        // booleans that it cannot vectorise), which made a 6000x6000 render of
        // testBackground take 291 ms on one thread instead of 144 ms. Blocks of 16 to
        // 128 columns measured alike.
        constexpr int kBlock = 64;
        Real hit[kBlock], near[kBlock], far[kBlock];
        for (int c0 = first; c0 <= last; c0 += kBlock) {
            const int n = last - c0 + 1 < kBlock ? last - c0 + 1 : kBlock;
            RT_VECTOR_LOOP
            for (int k = 0; k < n; ++k) {
                const LaneRoots<Real> r = unit_sphere_roots(ox, oy, oz, c_term, column_dx(c0 + k), dy, dz);
                hit[k] = r.hit, near[k] = r.near, far[k] = r.far;
            }
            RT_VECTOR_LOOP
            for (int k = 0; k < n; ++k) {
                const int c = c0 + k;
                // BruteForce::closest(); a NaN best t (no hit yet) makes !(t >= best t) true, and
                // an accepted t is never NaN, so that test is t < best t otherwise.
                const bool inside = !(near[k] > min_t);
                const Real t = inside ? far[k] : near[k];
                const bool accept = hit[k] != 0 && t > min_t && !(t >= best_t[c]);
                best_t[c] = accept ? t : best_t[c];
                best[c] = accept ? i : best[c];
                best_inside[c] = accept ? std::uint32_t(inside) : best_inside[c];
            }
        }
    }

    static constexpr std::size_t kMaxTable = std::size_t(1) << 18;  // entries: 2 MiB in double
    static constexpr std::size_t kNoTable = ~std::size_t(0);
    struct Terms {
        Vec3<Real> scale, o;  // s and o' = (camera - C) / s
        Real c;               // o'.o' - 1
        int first_column;     // of the tables
        std::size_t table;    // where its columns start in the tables, or kNoTable
    };
    std::vector<Terms> terms_;
    std::vector<Real> dx_;  // per ellipsoid and column, see the constructor
    Real min_t_;
};

}  // namespace rt
