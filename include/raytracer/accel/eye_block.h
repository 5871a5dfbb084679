// The eye rays of a block of pixels, Rows x Columns of them at most, against one
// ellipsoid at a time: what the tree's descent (Bvh::closest() for an EyeBlock) does in
// each ellipsoid whose box the block may meet, for the first bounce of WhittedTiles.
//
// WHY: every eye ray starts at the camera, so an ellipsoid's mapped origin o' and c are
// made once per block, d'.x = x / s.x once per column and d'.y, d'.z once per row: one
// division a pixel, where a bundle of rays from arbitrary origins pays three for d' and
// three more for its slab inverses. The rows are plain loops over the columns that GCC
// vectorises (build.vectorised_loops).
//
// Bit-identity: the loop runs the one root solver, unit_sphere_roots(), on the inputs
// intersect() gives it (o' and c of mapped_origin() of the camera, d' = direction / s),
// and the merge is the reference's: visible_root() beyond visible_beyond(1), the
// nearest root kept, equal roots to the lower index (NearestHit::replaced_by()), so the
// ellipsoids may come in any order. A row is skipped only where no lane's ray meets the
// ellipsoid's box before its nearest root so far (bvh.h: then it has no usable root).
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

#include "raytracer/accel/silhouette.h"
#include "raytracer/accel/slab_rays.h"
#include "raytracer/compiler.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/reference/unit_sphere_roots.h"
#include "raytracer/scene_precision.h"
#include "raytracer/vec3.h"

namespace rt {

// The eye rays of columns [first, last) of one row against one ellipsoid, the scene's
// ellipsoid `index`: o is mapped_origin() of the camera, column_dx(c) gives
// d'.x = x / s.x of column c, and dy, dz the row's d'.y = y / s.y, d'.z = near_z / s.z.
// Each column's nearest hit so far (best_t: infinity, best: kNoEllipsoid before the
// first) is replaced where the ellipsoid shows a nearer root, or an equal one at a lower
// index.
// Used by the tree's blocks (EyeBlock) and the flat sweep's rows (EyeRays).
template <int kBlock, typename Real, typename ColumnDx>
RT_ALWAYS_INLINE void merge_eye_row(const MappedOrigin<Real>& o, ColumnDx column_dx, Real dy, Real dz,
                                    std::uint32_t index, int first, int last, Real* best_t,
                                    std::uint32_t* best, std::uint32_t* best_inside) {
    const Real ox = o.o.x, oy = o.o.y, oz = o.o.z, c_term = o.c;
    const Real beyond = visible_beyond(Real(kEyeRayMinT));
    // The roots of a block of columns first, then their merge. WHY: GCC 12 keeps a loop
    // that does both scalar (it folds the solver's hit into a select of booleans that it
    // cannot vectorise), which made a 6000x6000 render of testBackground take 291 ms on
    // one thread instead of 144 ms.
    Real hit[kBlock], near[kBlock], far[kBlock];
    for (int c0 = first; c0 < last; c0 += kBlock) {
        const int n = last - c0 < kBlock ? last - c0 : kBlock;
        RT_VECTOR_LOOP
        for (int k = 0; k < n; ++k) {
            const Roots<Real> r = unit_sphere_roots(ox, oy, oz, c_term, column_dx(c0 + k), dy, dz);
            hit[k] = r.hit, near[k] = r.near, far[k] = r.far;
        }
        RT_VECTOR_LOOP
        for (int k = 0; k < n; ++k) {
            const int c = c0 + k;
            // visible_root(), then NearestHit::replaced_by() (kNoEllipsoid is above any index).
            const bool in = !(near[k] > beyond);
            const Real root = in ? far[k] : near[k];
            const bool accept =
                hit[k] != 0 && root > beyond && (root < best_t[c] || (root == best_t[c] && index < best[c]));
            best_t[c] = accept ? root : best_t[c];
            best[c] = accept ? index : best[c];
            best_inside[c] = accept ? std::uint32_t(in) : best_inside[c];
        }
    }
}

template <typename Real, int Rows, int Columns>
class EyeBlock {
public:
    using C = AtLeastDouble<Real>;  // the slab tests, as the tree's

    // The eye ray of row b and column c runs from the camera (0, 0, 0) along
    // (column_x[c], row_y[b], near_z), for b < rows <= Rows and c < columns <= Columns.
    EyeBlock(const Real* column_x, int columns, const Real* row_y, int rows, Real near_z)
        : near_z_(near_z), rows_(rows), columns_(columns) {
        assert(1 <= columns && columns <= Columns && 1 <= rows && rows <= Rows);
        // Columns past `columns` repeat the last one: the loops run over all of them, and
        // their hits are never asked for (they only repeat the last column's).
        for (int c = 0; c < Columns; ++c) x_[c] = column_x[std::min(c, columns - 1)];
        for (int b = 0; b < Rows; ++b) y_[b] = row_y[std::min(b, rows - 1)];
        x_lo_ = x_hi_ = C(x_[0]);
        for (int c = 1; c < Columns; ++c)
            x_lo_ = std::min(x_lo_, C(x_[c])), x_hi_ = std::max(x_hi_, C(x_[c]));
        using std::abs;
        margin_ = columns >= 2 ? 2 * abs(C(x_[1]) - C(x_[0])) : C(0);
    }

    // The directions' range, per axis, for a slab ray of the block's rays whose x (and y)
    // is below 0 where x_side (y_side) is -1, not below 0 where it is +1, any where 0;
    // false where no ray is on those sides. A NaN is left out (its ray has no visible root).
    bool directions(C (&lo)[3], C (&hi)[3], int x_side = 0, int y_side = 0) const {
        auto on_side = [](C v, int side) { return side == 0 || (side < 0) == (v < 0); };
        lo[0] = lo[1] = std::numeric_limits<C>::infinity(), hi[0] = hi[1] = -lo[0];
        for (int c = 0; c < Columns; ++c)
            if (on_side(C(x_[c]), x_side))
                lo[0] = std::min(lo[0], C(x_[c])), hi[0] = std::max(hi[0], C(x_[c]));
        for (int b = 0; b < Rows; ++b)
            if (on_side(C(y_[b]), y_side))
                lo[1] = std::min(lo[1], C(y_[b])), hi[1] = std::max(hi[1], C(y_[b]));
        lo[2] = hi[2] = C(near_z_);
        return lo[0] <= hi[0] && lo[1] <= hi[1];
    }

    int rows() const { return rows_; }
    int columns() const { return columns_; }
    Vec3<Real> direction(int b, int c) const { return {x_[c], y_[b], near_z_}; }

    // Whether some ellipsoid was tried (add(), take()); if not, no pixel has a hit.
    bool tried() const { return tried_; }
    // The hit of row b and column c (where tried()): a found one as Bvh::closest() gives
    // it; none has an infinite t.
    NearestHit<Real> hit(int b, int c) const { return {t_[b][c], ellipsoid_[b][c], inside_[b][c] != 0}; }
    // Sets it from a query of the pixel's ray alone.
    void take(int b, int c, const NearestHit<Real>& hit) {
        if (!tried_) set_up();
        t_[b][c] = hit.found() ? hit.t : std::numeric_limits<Real>::infinity();
        ellipsoid_[b][c] = hit.ellipsoid, inside_[b][c] = hit.inside ? 1 : 0;
    }
    // Infinity where some pixel has no hit yet; else the farthest of their roots.
    Real farthest() const {
        Real far = 0;
        for (int b = 0; b < rows_; ++b)
            for (int c = 0; c < Columns; ++c)
                far = ellipsoid_[b][c] == kNoEllipsoid ? std::numeric_limits<Real>::infinity()
                                                       : std::max(far, t_[b][c]);
        return far;
    }

    // Ellipsoid e, the scene's ellipsoid `index`, against every pixel; where box is given
    // (e's inflated box, from a camera within its guard: bvh.h), only in the rows with a
    // ray that may meet the box before its pixel's nearest root so far.
    void add(const Ellipsoid<Real>& e, std::uint32_t index, const BuildBox<C>* box = nullptr) {
        if (!tried_) set_up();
        C x_enter[Columns], x_leave[Columns], z_enter = 0, z_leave = std::numeric_limits<C>::infinity();
        if (box != nullptr) {
            RT_VECTOR_LOOP
            for (int c = 0; c < Columns; ++c) {
                x_enter[c] = 0, x_leave[c] = std::numeric_limits<C>::infinity();
                clip_to_slab(box->lo[0] * inverse_x_[c], box->hi[0] * inverse_x_[c], x_enter[c], x_leave[c]);
            }
            clip_to_slab(box->lo[2] * inverse_z_, box->hi[2] * inverse_z_, z_enter, z_leave);
        }
        const MappedOrigin<Real> o = mapped_origin(e, Vec3<Real>{});
        Real dx[Columns];
        const Real sx = e.scale.x;
        RT_VECTOR_LOOP
        for (int c = 0; c < Columns; ++c) dx[c] = x_[c] / sx;
        // Rows outside the silhouette are skipped too, where pixels are apart (silhouette.h),
        // and only where a box was met: add() without one (Bvh's add_all()) is the
        // unculled fallback, and stays unculled.
        const Silhouette<C> silhouette(e, C(near_z_));
        const bool narrow = box != nullptr && margin_ > 0;
        for (int b = 0; b < rows_; ++b) {
            if (box != nullptr && !row_may_meet(*box, b, x_enter, x_leave, z_enter, z_leave)) continue;
            if (narrow && !silhouette.row_may_meet(C(y_[b]), x_lo_, x_hi_, margin_)) continue;
            merge_eye_row<Columns>(
                o, [&](int c) { return dx[c]; }, y_[b] / e.scale.y, near_z_ / e.scale.z, index, 0, Columns,
                t_[b], ellipsoid_[b], inside_[b]);
        }
    }

private:
    // What the first add() needs: a block that meets no box (most of a course scene's
    // background) does without it.
    void set_up() {
        tried_ = true;
        auto inverse = [this](Real d) {
            const C inv = 1 / C(d);
            unculled_ = unculled_ || unbounded_inverse(C(d), inv);
            return inv;
        };
        for (int c = 0; c < Columns; ++c) inverse_x_[c] = inverse(x_[c]);
        for (int b = 0; b < Rows; ++b) inverse_y_[b] = inverse(y_[b]);
        inverse_z_ = inverse(near_z_);
        for (int b = 0; b < Rows; ++b)
            for (int c = 0; c < Columns; ++c)
                t_[b][c] = std::numeric_limits<Real>::infinity(), ellipsoid_[b][c] = kNoEllipsoid,
                inside_[b][c] = 0;
    }

    // Whether some eye ray of row b may meet the box before its pixel's nearest root:
    // the slab test of LaneRays::meeting() (slab_rays.h) for rays from the camera, from
    // the columns' x slabs and the z slab.
    bool row_may_meet(const BuildBox<C>& box, int b, const C (&x_enter)[Columns], const C (&x_leave)[Columns],
                      C z_enter, C z_leave) const {
        if (unculled_) return true;
        C enter = z_enter, leave = z_leave;
        clip_to_slab(box.lo[1] * inverse_y_[b], box.hi[1] * inverse_y_[b], enter, leave);
        if (!(enter <= leave)) return false;
        const Real* const best_t = t_[b];
        int met = 0;
        RT_VECTOR_LOOP
        for (int c = 0; c < Columns; ++c) {
            const C from = x_enter[c] > enter ? x_enter[c] : enter;
            C to = x_leave[c] < leave ? x_leave[c] : leave;
            to = C(best_t[c]) < to ? C(best_t[c]) : to;
            met |= from <= to ? 1 : 0;
        }
        return met != 0;
    }

    Real x_[Columns], y_[Rows], near_z_;
    C x_lo_, x_hi_, margin_;  // the columns' range, and two pixels' spacing (0: one column)
    // Each pixel's nearest hit so far: root t of ellipsoid (kNoEllipsoid: none yet), inside
    // when the far root was taken. As wide as the index: with mixed widths GCC's vector
    // code packs and unpacks the lanes.
    Real t_[Rows][Columns];
    // 1 / the directions' components per column and row, and for z; unculled_ where one
    // of a non-zero component is not finite (a pixel's x or y may be subnormal where the
    // block's range, which the descent's slab ray takes, is not): then every box is met.
    C inverse_x_[Columns], inverse_y_[Rows], inverse_z_;
    std::uint32_t ellipsoid_[Rows][Columns], inside_[Rows][Columns];
    int rows_, columns_;
    bool tried_ = false, unculled_ = false;
};

}  // namespace rt
