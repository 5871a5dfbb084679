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
// Bit-identity: the loops are merge_eye_row()'s (eye_block.h, the tree's too): the one
// root solver, unit_sphere_roots(), on the inputs intersect_mapped() gives it (o' and c
// of mapped_origin(), d' = direction / s), and the reference's merge (visible_root(),
// NearestHit::replaced_by()). d'.y = y / s.y and d'.z = near_z / s.z are computed once
// per row, d'.x = x / s.x once per column: the same operations on the same values.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "raytracer/accel/eye_block.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/vec3.h"

namespace rt {

// Per column of the image (one per row of a thread's band): the nearest hit found so far
// in the row.
template <typename Real>
struct EyeRowHits {
    OwnLinesVector<Real> t;                   // infinity until a hit is accepted
    OwnLinesVector<std::uint32_t> ellipsoid;  // kNoEllipsoid until a hit is accepted
    // The far root was taken (0 or 1). As wide as the index: with mixed widths GCC's
    // vector code packs and unpacks the lanes (2.5 % more instructions on the course scenes).
    OwnLinesVector<std::uint32_t> inside;

    explicit EyeRowHits(int columns)
        : t(static_cast<std::size_t>(columns)),
          ellipsoid(static_cast<std::size_t>(columns)),
          inside(static_cast<std::size_t>(columns)) {}
};

template <typename Real>
class EyeRays {
public:
    // ellipsoids[i] and origins[i] (mapped_origin() of the camera) for every ellipsoid;
    // column_x[c] the x of column c's eye ray; columns [first_column[i], last_column[i]]
    // the only ones ever asked of ellipsoid i.
    EyeRays(const std::vector<Ellipsoid<Real>>& ellipsoids, const std::vector<MappedOrigin<Real>>& origins,
            const std::vector<Real>& column_x, const std::vector<int>& first_column,
            const std::vector<int>& last_column) {
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
            hits.t[static_cast<std::size_t>(c)] = std::numeric_limits<Real>::infinity();
            hits.ellipsoid[static_cast<std::size_t>(c)] = kNoEllipsoid;
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
            merge_columns(hits, i, first, last, y, near_z, [&](int c) { return dx[c]; });
        } else {
            const Real sx = e.scale.x;
            merge_columns(hits, i, first, last, y, near_z, [&](int c) { return column_x[c] / sx; });
        }
    }

private:
    // merge_eye_row() for ellipsoid i; column_dx(c) gives d'.x = x / s.x of column c.
    // Blocks of 16 to 128 columns measured alike.
    template <typename ColumnDx>
    void merge_columns(EyeRowHits<Real>& hits, std::uint32_t i, int first, int last, Real y, Real near_z,
                       ColumnDx column_dx) const {
        const Terms& e = terms_[i];
        merge_eye_row<64>(MappedOrigin<Real>{e.o, e.c}, column_dx, y / e.scale.y, near_z / e.scale.z, i,
                          first, last + 1, hits.t.data(), hits.ellipsoid.data(), hits.inside.data());
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
};

}  // namespace rt
