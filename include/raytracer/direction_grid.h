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

    // Cells of size 2/n on each cube face (n >= 1).
    DirectionGrid(C px, C py, C pz, const std::vector<BoundingSphere<C>>& spheres, int n)
        : x_(px), y_(py), z_(pz), n_(n) {
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
        for (int face = 0; face < 6; ++face)
            for (int row = 0; row < n; ++row)
                for (int col = 0; col < n; ++col) {
                    // The cell's centre direction and the cosine and sine of the largest
                    // angle from it to a corner (a cone that contains the cell).
                    C cx, cy, cz;
                    unit_direction(face, (C(col) + C(0.5)) * 2 / C(n) - 1, (C(row) + C(0.5)) * 2 / C(n) - 1,
                                   cx, cy, cz);
                    C cos_a = 1;
                    for (int corner = 0; corner < 4; ++corner) {
                        C kx, ky, kz;
                        unit_direction(face, C(col + (corner & 1)) * 2 / C(n) - 1,
                                       C(row + (corner >> 1)) * 2 / C(n) - 1, kx, ky, kz);
                        cos_a = std::min(cos_a, cx * kx + cy * ky + cz * kz);
                    }
                    const C sin_a = sqrt(std::max(C(0), C(1) - cos_a * cos_a));
                    for (std::size_t i = 0; i < spheres.size(); ++i) {
                        const Seen& v = seen[i];
                        // Angle(centre, sphere) <= a + b, in cosines (a + b < pi, as a is
                        // at most 55 degrees and b below 90): cos(theta) >= cos(a + b).
                        const bool listed =
                            v.everywhere || cx * v.ux + cy * v.uy + cz * v.uz >=
                                                (cos_a * v.cos_b - sin_a * v.sin_b) - kAngleMargin;
                        if (listed) items_.push_back(static_cast<std::uint32_t>(i));
                    }
                    offsets_.push_back(static_cast<std::uint32_t>(items_.size()));
                }
    }

    // The ellipsoids that a ray from X in direction (dx, dy, dz) may meet: [first, last).
    const std::uint32_t* list(C dx, C dy, C dz, const std::uint32_t** last) const {
        using std::abs;
        const C ax = abs(dx), ay = abs(dy), az = abs(dz);
        int face;
        C u, v, m;
        if (ax >= ay && ax >= az) {
            face = dx > 0 ? 0 : 1, u = dy, v = dz, m = ax;
        } else if (ay >= az) {
            face = dy > 0 ? 2 : 3, u = dx, v = dz, m = ay;
        } else {
            face = dz > 0 ? 4 : 5, u = dx, v = dy, m = az;
        }
        const std::size_t cell = (static_cast<std::size_t>(face) * static_cast<std::size_t>(n_) +
                                  static_cast<std::size_t>(index(v / m))) *
                                     static_cast<std::size_t>(n_) +
                                 static_cast<std::size_t>(index(u / m));
        *last = items_.data() + offsets_[cell + 1];
        return items_.data() + offsets_[cell];
    }

    C x() const { return x_; }
    C y() const { return y_; }
    C z() const { return z_; }

private:
    // Far above the rounding of a lookup (a few ulps of a direction) and of the cone
    // test; small against a cell (2/n of a face).
    static constexpr double kAngleMargin = 1e-6;

    // Cell index along one face axis of a coordinate in [-1, 1]; NaN gives 0.
    int index(C w) const {
        const C k = (w + 1) * C(n_) / 2;
        if (!(k > 0)) return 0;
        return k >= C(n_) ? n_ - 1 : static_cast<int>(k);
    }

    // The unit direction through face coordinates (u, v), both in [-1, 1].
    static void unit_direction(int face, C u, C v, C& dx, C& dy, C& dz) {
        using std::sqrt;
        const C sign = (face & 1) ? C(-1) : C(1);
        if (face < 2) {
            dx = sign, dy = u, dz = v;
        } else if (face < 4) {
            dx = u, dy = sign, dz = v;
        } else {
            dx = u, dy = v, dz = sign;
        }
        const C len = sqrt(dx * dx + dy * dy + dz * dz);
        dx /= len, dy /= len, dz /= len;
    }

    C x_ = 0, y_ = 0, z_ = 0;
    int n_ = 1;
    std::vector<std::uint32_t> offsets_;  // cell k lists items_[offsets_[k], offsets_[k + 1])
    std::vector<std::uint32_t> items_;
};

}  // namespace rt
