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

#include "raytracer/bit_scan.h"

namespace rt {

// A bounding sphere, in double (or wider) precision.
template <typename C>
struct BoundingSphere {
    C x, y, z, radius;
};

// A sphere as seen from a point: its distance, unit direction, and the sine and cosine
// of its angular radius; a sphere around the point (its radius widened by margin) or
// at a NaN distance is seen in every direction, and nothing else is set.
template <typename C>
struct SeenSphere {
    C distance, ux, uy, uz, sin_b, cos_b;
    bool everywhere;
};

template <typename C>
SeenSphere<C> seen_from(C px, C py, C pz, const BoundingSphere<C>& s, double margin) {
    using std::sqrt;
    SeenSphere<C> v{};
    const C wx = s.x - px, wy = s.y - py, wz = s.z - pz;
    v.distance = sqrt(wx * wx + wy * wy + wz * wz);
    v.everywhere = !(v.distance > s.radius * (C(1) + C(margin)));
    if (v.everywhere) return v;
    v.ux = wx / v.distance, v.uy = wy / v.distance, v.uz = wz / v.distance;
    v.sin_b = s.radius / v.distance;
    v.cos_b = sqrt(C(1) - v.sin_b * v.sin_b);
    return v;
}

template <typename C>
class DirectionGrid {
public:
    DirectionGrid() = default;

    // The cones that contain the cells, in a face's own coordinates (w along the face's
    // axis, outward; u and v as in list()), as arrays over the cells (row-major): the
    // same for the cell at (row, col) of each of the six faces, so computed once for all
    // faces and all lights. Per cell: the unit direction (w, u, v) through its centre,
    // and the cosine and sine of the largest angle from it to a corner of the cell.
    struct CellCones {
        std::vector<C> w, u, v, cos_a, sin_a;
    };
    static CellCones cell_cones(int n) {
        using std::sqrt;
        // The unit direction through each corner of the n x n cells, once per corner
        // (neighbouring cells share them): the same operations as per cell, so the same
        // values.
        const auto side = static_cast<std::size_t>(n) + 1;
        std::vector<C> corner_w(side * side), corner_u(side * side), corner_v(side * side);
        for (int row = 0; row <= n; ++row)
            for (int col = 0; col <= n; ++col) {
                const std::size_t at = static_cast<std::size_t>(row) * side + static_cast<std::size_t>(col);
                unit_direction(C(col) * 2 / C(n) - 1, C(row) * 2 / C(n) - 1, corner_w[at], corner_u[at],
                               corner_v[at]);
            }
        CellCones cones;
        const std::size_t cells = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
        for (std::vector<C>* a : {&cones.w, &cones.u, &cones.v, &cones.cos_a, &cones.sin_a}) a->resize(cells);
        for (int row = 0; row < n; ++row)
            for (int col = 0; col < n; ++col) {
                const std::size_t k = static_cast<std::size_t>(row) * static_cast<std::size_t>(n) +
                                      static_cast<std::size_t>(col);
                C w, u, v;
                unit_direction((C(col) + C(0.5)) * 2 / C(n) - 1, (C(row) + C(0.5)) * 2 / C(n) - 1, w, u, v);
                C cos_a = 1;
                for (int corner = 0; corner < 4; ++corner) {
                    const std::size_t at = static_cast<std::size_t>(row + (corner >> 1)) * side +
                                           static_cast<std::size_t>(col + (corner & 1));
                    cos_a = std::min(cos_a, w * corner_w[at] + u * corner_u[at] + v * corner_v[at]);
                }
                cones.w[k] = w, cones.u[k] = u, cones.v[k] = v, cones.cos_a[k] = cos_a;
                cones.sin_a[k] = sqrt(std::max(C(0), C(1) - cos_a * cos_a));
            }
        return cones;
    }

    // Cells of size 2/n on each cube face (n >= 1).
    DirectionGrid(C px, C py, C pz, const std::vector<BoundingSphere<C>>& spheres, int n)
        : DirectionGrid(px, py, pz, spheres, n, cell_cones(n)) {}

    // The same with the cones of cell_cones(n), shared by the grids of all lights.
    DirectionGrid(C px, C py, C pz, const std::vector<BoundingSphere<C>>& spheres, int n,
                  const CellCones& cones)
        : x_(px), y_(py), z_(pz), n_(n), half_n_(C(n) / 2) {
        const std::size_t face_cells = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
        const std::size_t cells = 6 * face_cells;
        std::vector<SeenSphere<C>> seen;
        seen.reserve(spheres.size());
        for (const BoundingSphere<C>& s : spheres) seen.push_back(seen_from(px, py, pz, s, kAngleMargin));
        // Each cell's list as a bit set (bit i: sphere i), sphere by sphere over all the
        // cells of a face: vector instructions, each cell's test the same operations.
        // Where there are more spheres than bits, cell by cell into the lists directly.
        const bool as_bits = spheres.size() <= kMaxBitsEllipsoids;
        if (as_bits) bits_.assign(cells, 0);
        offsets_.reserve(cells + 1);
        offsets_.push_back(0);
        for (int face = 0; face < 6; ++face) {
            const C sign = (face & 1) ? C(-1) : C(1);
            // Sphere i's direction in the face's coordinates (w, u, v), so that its angle
            // to a cell's centre is a dot product with the cell's cone.
            auto local = [&](const SeenSphere<C>& v, C& w, C& u, C& t) {
                if (face < 2) {
                    w = sign * v.ux, u = v.uy, t = v.uz;
                } else if (face < 4) {
                    w = sign * v.uy, u = v.ux, t = v.uz;
                } else {
                    w = sign * v.uz, u = v.ux, t = v.uy;
                }
            };
            // Angle(centre, sphere) <= a + b, in cosines (a + b < pi, as a is at most 55
            // degrees and b below 90): cos(theta) >= cos(a + b). The rounding of the face
            // coordinates (an ulp) is far below the margin.
            if (as_bits) {
                std::uint64_t* const face_bits = bits_.data() + static_cast<std::size_t>(face) * face_cells;
                for (std::size_t i = 0; i < spheres.size(); ++i) {
                    const SeenSphere<C>& v = seen[i];
                    const std::uint64_t bit = std::uint64_t(1) << i;
                    if (v.everywhere) {
                        for (std::size_t k = 0; k < face_cells; ++k) face_bits[k] |= bit;
                        continue;
                    }
                    C lw, lu, lv;
                    local(v, lw, lu, lv);
                    const C cos_b = v.cos_b, sin_b = v.sin_b;
                    for (std::size_t k = 0; k < face_cells; ++k) {
                        const bool listed = cones.w[k] * lw + cones.u[k] * lu + cones.v[k] * lv >=
                                            (cones.cos_a[k] * cos_b - cones.sin_a[k] * sin_b) - kAngleMargin;
                        face_bits[k] |= listed ? bit : 0;
                    }
                }
                continue;
            }
            for (std::size_t k = 0; k < face_cells; ++k) {
                for (const SeenSphere<C>& v : seen) {
                    bool listed = v.everywhere;
                    if (!listed) {
                        C lw, lu, lv;
                        local(v, lw, lu, lv);
                        listed = cones.w[k] * lw + cones.u[k] * lu + cones.v[k] * lv >=
                                 (cones.cos_a[k] * v.cos_b - cones.sin_a[k] * v.sin_b) - kAngleMargin;
                    }
                    if (listed) items_.push_back(static_cast<std::uint32_t>(&v - seen.data()));
                }
                offsets_.push_back(static_cast<std::uint32_t>(items_.size()));
            }
        }
        if (!as_bits) return;
        // The lists from the bit sets, in increasing order, in one allocation.
        std::size_t listed = 0;
        for (const std::uint64_t b : bits_) listed += static_cast<std::size_t>(bit_count(b));
        items_.reserve(listed);
        for (std::uint64_t b : bits_) {
            for (std::uint32_t i = 0; b != 0; ++i, b >>= 1)
                if ((b & 1U) != 0) items_.push_back(i);
            offsets_.push_back(static_cast<std::uint32_t>(items_.size()));
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
