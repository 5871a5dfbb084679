// A "light buffer" (Haines and Greenberg, 1986): around a fixed point X (a light), a
// cube of directions cut into N x N cells per face; each cell lists, in
// increasing order, the ellipsoids whose bounding sphere some ray from X through the
// cell may meet. A shadow ray then intersects only its cell's list.
//
// WHY: every shadow ray from a hit point to a light lies on the line through the
// light, so one table per light, built once, replaces a test against every ellipsoid
// per ray. The test is conservative: the bounding sphere is inflated (see
// sphere_bounds.h) and the cone of a cell widened by kAngleMargin, far above the
// rounding of the lookup, so a culled ellipsoid is one that intersect() would have
// missed; images stay bit-identical. Measured gain in docs/speed.md.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/vec3.h"

namespace rt {

// A bounding sphere, in double (or wider) precision.
template <typename C>
struct BoundingSphere {
    C x, y, z, radius;
};

template <typename C>
class DirectionGrid {
public:
    DirectionGrid() = default;

    // The cone that contains a cell, in its face's own coordinates (w along the face's
    // axis, outward; u and v as in list()): the same for the cell at (row, col) of
    // each of the six faces, so computed once for all faces and all lights.
    struct CellCone {
        C w, u, v;       // the unit direction through the cell's centre
        C cos_a, sin_a;  // of the largest angle from it to a corner of the cell
    };
    static std::vector<CellCone> cell_cones(int n) {
        using std::sqrt;
        std::vector<CellCone> cones;
        cones.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
        for (int row = 0; row < n; ++row)
            for (int col = 0; col < n; ++col) {
                CellCone k{};
                unit_direction((C(col) + C(0.5)) * 2 / C(n) - 1, (C(row) + C(0.5)) * 2 / C(n) - 1, k.w, k.u,
                               k.v);
                k.cos_a = 1;
                for (int corner = 0; corner < 4; ++corner) {
                    C kw, ku, kv;
                    unit_direction(C(col + (corner & 1)) * 2 / C(n) - 1,
                                   C(row + (corner >> 1)) * 2 / C(n) - 1, kw, ku, kv);
                    k.cos_a = std::min(k.cos_a, k.w * kw + k.u * ku + k.v * kv);
                }
                k.sin_a = sqrt(std::max(C(0), C(1) - k.cos_a * k.cos_a));
                cones.push_back(k);
            }
        return cones;
    }

    // Cells of size 2/n on each cube face (n >= 1).
    DirectionGrid(C px, C py, C pz, const std::vector<BoundingSphere<C>>& spheres, int n)
        : DirectionGrid(px, py, pz, spheres, n, cell_cones(n)) {}

    // The same with the cones of cell_cones(n), shared by the grids of all lights.
    DirectionGrid(C px, C py, C pz, const std::vector<BoundingSphere<C>>& spheres, int n,
                  const std::vector<CellCone>& cones)
        : x_(px), y_(py), z_(pz), n_(n), half_n_(C(n) / 2) {
        using std::sqrt;
        const std::size_t cells = 6 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
        offsets_.reserve(cells + 1);
        offsets_.push_back(0);
        // Per sphere: its unit direction from X and the sine and cosine of its angular
        // radius; a sphere around X is seen in every direction.
        struct Seen {
            C ux, uy, uz, sin_b, cos_b;
            bool everywhere;
        };
        std::vector<Seen> seen(spheres.size());
        for (std::size_t i = 0; i < spheres.size(); ++i) {
            const BoundingSphere<C>& s = spheres[i];
            const C wx = s.x - px, wy = s.y - py, wz = s.z - pz;
            const C dist = sqrt(wx * wx + wy * wy + wz * wz);
            Seen& v = seen[i];
            v.everywhere = !(dist > s.radius * (C(1) + kAngleMargin));
            if (v.everywhere) continue;
            v.ux = wx / dist, v.uy = wy / dist, v.uz = wz / dist;
            v.sin_b = s.radius / dist;
            v.cos_b = sqrt(C(1) - v.sin_b * v.sin_b);
        }
        // Per face, each sphere's direction in the face's coordinates (w, u, v), so that
        // its angle to a cell's centre is a dot product with the cell's cone.
        struct Local {
            C w, u, v, sin_b, cos_b;
            bool everywhere;
        };
        std::vector<Local> local(spheres.size());
        auto locals = [&](int face) {
            const C sign = (face & 1) ? C(-1) : C(1);
            for (std::size_t i = 0; i < spheres.size(); ++i) {
                const Seen& v = seen[i];
                Local& l = local[i];
                l.everywhere = v.everywhere, l.sin_b = v.sin_b, l.cos_b = v.cos_b;
                if (v.everywhere) continue;
                if (face < 2) {
                    l.w = sign * v.ux, l.u = v.uy, l.v = v.uz;
                } else if (face < 4) {
                    l.w = sign * v.uy, l.u = v.ux, l.v = v.uz;
                } else {
                    l.w = sign * v.uz, l.u = v.ux, l.v = v.uy;
                }
            }
        };
        // Angle(centre, sphere) <= a + b, in cosines (a + b < pi, as a is at most 55
        // degrees and b below 90): cos(theta) >= cos(a + b). The rounding of the face
        // coordinates (an ulp) is far below the margin.
        auto listed = [](const CellCone& k, const Local& l) {
            return l.everywhere || k.w * l.w + k.u * l.u + k.v * l.v >=
                                       (k.cos_a * l.cos_b - k.sin_a * l.sin_b) - kAngleMargin;
        };
        if (spheres.size() <= kMaxBitsEllipsoids) {
            // The lists as bit sets first, sphere by sphere over all cells of a face (a loop
            // over the cells that GCC vectorises; the same test per cell and sphere), then
            // the lists from the sets, in increasing order as below.
            // WHY: the grids of the course scenes (1 to 3 spheres) cost more to build than
            // to use; per cell and sphere the loop below was branches and push_backs.
            const std::size_t per_face = cones.size();
            std::vector<C> cw(per_face), cu(per_face), cv(per_face), ccos(per_face), csin(per_face);
            for (std::size_t c = 0; c < per_face; ++c)
                cw[c] = cones[c].w, cu[c] = cones[c].u, cv[c] = cones[c].v, ccos[c] = cones[c].cos_a,
                csin[c] = cones[c].sin_a;
            bits_.assign(cells, 0);
            for (int face = 0; face < 6; ++face) {
                locals(face);
                std::uint64_t* face_bits = bits_.data() + std::size_t(face) * per_face;
                for (std::size_t i = 0; i < spheres.size(); ++i) {
                    const Local l = local[i];
                    const std::uint64_t bit = std::uint64_t(1) << i;
                    if (l.everywhere) {
                        for (std::size_t c = 0; c < per_face; ++c) face_bits[c] |= bit;
                        continue;
                    }
                    for (std::size_t c = 0; c < per_face; ++c)
                        face_bits[c] |= cw[c] * l.w + cu[c] * l.u + cv[c] * l.v >=
                                                (ccos[c] * l.cos_b - csin[c] * l.sin_b) - kAngleMargin
                                            ? bit
                                            : 0;
                }
            }
            for (std::size_t cell = 0; cell < cells; ++cell) {
                for (std::uint64_t set = bits_[cell]; set != 0; set &= set - 1) {
                    std::uint32_t i = 0;
                    while (((set >> i) & 1U) == 0) ++i;
                    items_.push_back(i);
                }
                offsets_.push_back(static_cast<std::uint32_t>(items_.size()));
            }
            return;
        }
        for (int face = 0; face < 6; ++face) {
            locals(face);
            for (const CellCone& k : cones) {
                for (std::size_t i = 0; i < spheres.size(); ++i)
                    if (listed(k, local[i])) items_.push_back(static_cast<std::uint32_t>(i));
                offsets_.push_back(static_cast<std::uint32_t>(items_.size()));
            }
        }
    }

    // The ellipsoids that a ray from X in direction (dx, dy, dz) may meet: [first, last).
    const std::uint32_t* list(C dx, C dy, C dz, const std::uint32_t** last) const {
        return cell_list(cell(dx, dy, dz), last);
    }

    // The same in two steps: the number of the cell that direction falls in, then its list.
    // cells() finds the cells of N directions at once (vector instructions, the same
    // operations as cell(), so the same cells).
    std::int32_t cell(C dx, C dy, C dz) const {
        using std::abs;
        const C ax = abs(dx), ay = abs(dy), az = abs(dz);
        // The face of the largest coordinate, as selects rather than branches.
        const bool x_major = ax >= ay && ax >= az;
        const bool y_major = !x_major && ay >= az;
        const std::int32_t face = x_major ? (dx > 0 ? 0 : 1) : y_major ? (dy > 0 ? 2 : 3) : (dz > 0 ? 4 : 5);
        const C u = x_major ? dy : dx;
        const C v = x_major || y_major ? dz : dy;
        const C m = x_major ? ax : y_major ? ay : az;
        // One reciprocal for both coordinates: an ulp more rounding, far inside kAngleMargin.
        const C scale = half_n_ / m;
        return (face * n_ + index(v * scale + half_n_)) * n_ + index(u * scale + half_n_);
    }
    template <int N>
    void cells(const C* dx, const C* dy, const C* dz, std::int32_t* out) const {
        for (int k = 0; k < N; ++k) out[k] = cell(dx[k], dy[k], dz[k]);
    }
    const std::uint32_t* cell_list(std::int32_t cell, const std::uint32_t** last) const {
        *last = items_.data() + offsets_[static_cast<std::size_t>(cell) + 1];
        return items_.data() + offsets_[static_cast<std::size_t>(cell)];
    }

    // A cell's list as a bit set (bit i: ellipsoid i), where has_bits(): at most 64
    // ellipsoids.
    bool has_bits() const { return !bits_.empty(); }
    std::uint64_t cell_bits(std::int32_t cell) const { return bits_[static_cast<std::size_t>(cell)]; }
    static constexpr std::size_t kMaxBitsEllipsoids = 64;

    C x() const { return x_; }
    C y() const { return y_; }
    C z() const { return z_; }

private:
    // Far above the rounding of a lookup (a few ulps of a direction) and of the cone
    // test; small against a cell (2/n of a face).
    static constexpr double kAngleMargin = 1e-6;

    // Cell index along one face axis of k = (w + 1) n / 2 for a coordinate w in [-1, 1];
    // NaN gives 0.
    std::int32_t index(C k) const {
        const C positive = k > 0 ? k : C(0);
        return positive >= C(n_) ? n_ - 1 : static_cast<std::int32_t>(positive);
    }

    // The unit direction through face coordinates (u, v), both in [-1, 1], in the face's
    // own coordinates (w along its axis).
    static void unit_direction(C u, C v, C& dw, C& du, C& dv) {
        using std::sqrt;
        const C len = sqrt(C(1) + u * u + v * v);
        dw = C(1) / len, du = u / len, dv = v / len;
    }

    C x_ = 0, y_ = 0, z_ = 0;
    std::int32_t n_ = 1;
    C half_n_ = C(0.5);                   // n / 2, exact
    std::vector<std::uint32_t> offsets_;  // cell k lists items_[offsets_[k], offsets_[k + 1])
    std::vector<std::uint32_t> items_;
    std::vector<std::uint64_t> bits_;  // per cell, when at most 64 ellipsoids
};

}  // namespace rt
