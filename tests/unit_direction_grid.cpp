// The light buffers' tables (direction_grid.h) against a plain construction: each
// cell's cone and list computed cell by cell, sphere by sphere, as the first version
// of DirectionGrid did. The vectorised construction must give the same cones, bit for
// bit, and the same lists (as lists and as bit sets); and every list must hold each
// sphere that a ray from the light through the cell meets (the buffer is conservative).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "check.h"
#include "random_checks.h"
#include "raytracer/flat_sweep/direction_grid.h"

namespace {

using Grid = rt::DirectionGrid<double>;
using Sphere = rt::BoundingSphere<double>;

void unit_direction(double u, double v, double& w, double& du, double& dv) {
    const double len = std::sqrt(1.0 + u * u + v * v);
    w = 1.0 / len, du = u / len, dv = v / len;
}

struct Cone {
    double w, u, v, cos_a, sin_a;
};

Cone plain_cone(int n, int row, int col) {
    Cone k{};
    unit_direction((double(col) + 0.5) * 2 / double(n) - 1, (double(row) + 0.5) * 2 / double(n) - 1, k.w, k.u,
                   k.v);
    k.cos_a = 1;
    for (int corner = 0; corner < 4; ++corner) {
        double kw, ku, kv;
        unit_direction(double(col + (corner & 1)) * 2 / double(n) - 1,
                       double(row + (corner >> 1)) * 2 / double(n) - 1, kw, ku, kv);
        k.cos_a = std::min(k.cos_a, k.w * kw + k.u * ku + k.v * kv);
    }
    k.sin_a = std::sqrt(std::max(0.0, 1.0 - k.cos_a * k.cos_a));
    return k;
}

// The list of cell (face, row, col), as the first version built it.
std::vector<std::uint32_t> plain_list(double px, double py, double pz, const std::vector<Sphere>& spheres,
                                      int n, int face, int row, int col) {
    constexpr double kMargin = 1e-6;
    const Cone k = plain_cone(n, row, col);
    const double sign = (face & 1) ? -1.0 : 1.0;
    std::vector<std::uint32_t> list;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        const Sphere& s = spheres[i];
        const double wx = s.x - px, wy = s.y - py, wz = s.z - pz;
        const double dist = std::sqrt(wx * wx + wy * wy + wz * wz);
        bool listed = !(dist > s.radius * (1 + kMargin));
        if (!listed) {
            const double ux = wx / dist, uy = wy / dist, uz = wz / dist;
            const double sin_b = s.radius / dist, cos_b = std::sqrt(1 - sin_b * sin_b);
            double lw, lu, lv;
            if (face < 2) {
                lw = sign * ux, lu = uy, lv = uz;
            } else if (face < 4) {
                lw = sign * uy, lu = ux, lv = uz;
            } else {
                lw = sign * uz, lu = ux, lv = uy;
            }
            listed = k.w * lw + k.u * lu + k.v * lv >= (k.cos_a * cos_b - k.sin_a * sin_b) - kMargin;
        }
        if (listed) list.push_back(static_cast<std::uint32_t>(i));
    }
    return list;
}

std::vector<Sphere> random_spheres(std::mt19937& g, int count, double px, double py, double pz) {
    std::uniform_real_distribution<double> at(-10, 10), size(0.01, 3);
    std::vector<Sphere> spheres;
    spheres.reserve(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i < count; ++i) spheres.push_back({at(g), at(g), at(g), size(g)});
    spheres.push_back({px + 0.1, py, pz, 0.5});  // around the light: seen everywhere
    return spheres;
}

}  // namespace

TEST(cones_equal_the_cell_by_cell_cones) {
    for (int n : {1, 2, 5, 16}) {
        const Grid::CellCones cones = Grid::cell_cones(n);
        for (int row = 0; row < n; ++row)
            for (int col = 0; col < n; ++col) {
                const Cone k = plain_cone(n, row, col);
                const std::size_t at = static_cast<std::size_t>(row) * static_cast<std::size_t>(n) +
                                       static_cast<std::size_t>(col);
                CHECK(cones.w[at] == k.w && cones.u[at] == k.u && cones.v[at] == k.v);
                CHECK(cones.cos_a[at] == k.cos_a && cones.sin_a[at] == k.sin_a);
            }
    }
}

TEST(lists_equal_the_cell_by_cell_lists) {
    std::mt19937 g(7);
    std::uniform_real_distribution<double> at(-5, 5);
    for (int count : {0, 3, 14, 63, 70}) {  // 70 + 1 spheres: no bit sets
        for (int trial = 0; trial < 3; ++trial) {
            const double px = at(g), py = at(g), pz = at(g);
            const std::vector<Sphere> spheres = random_spheres(g, count, px, py, pz);
            const int n = 16;
            const Grid grid(px, py, pz, spheres, n);
            CHECK_EQ(grid.has_bits(), spheres.size() <= Grid::kMaxBitsEllipsoids);
            for (int face = 0; face < 6; ++face)
                for (int row = 0; row < n; ++row)
                    for (int col = 0; col < n; ++col) {
                        const auto cell = static_cast<std::int32_t>((face * n + row) * n + col);
                        const std::uint32_t* last = nullptr;
                        const std::uint32_t* first = grid.cell_list(cell, &last);
                        const std::vector<std::uint32_t> expected =
                            plain_list(px, py, pz, spheres, n, face, row, col);
                        CHECK(std::vector<std::uint32_t>(first, last) == expected);
                        if (!grid.has_bits()) continue;
                        std::uint64_t bits = 0;
                        for (std::uint32_t i : expected) bits |= std::uint64_t(1) << i;
                        CHECK_EQ(grid.cell_bits(cell), bits);
                    }
        }
    }
}

// A ray from the light towards a point of a sphere finds the sphere in its cell's list.
TEST(every_sphere_a_ray_meets_is_in_its_cells_list) {
    std::mt19937 g(11);
    std::uniform_real_distribution<double> at(-5, 5), unit(-1, 1);
    for (int trial = 0; trial < 20; ++trial) {
        const double px = at(g), py = at(g), pz = at(g);
        const std::vector<Sphere> spheres = random_spheres(g, 20, px, py, pz);
        const Grid grid(px, py, pz, spheres, 16);
        for (std::uint32_t i = 0; i < spheres.size(); ++i)
            for (int ray = 0; ray < 200; ++ray) {
                double x = unit(g), y = unit(g), z = unit(g);
                const double len = std::sqrt(x * x + y * y + z * z);
                const Sphere& s = spheres[i];
                // A point inside the sphere, then the ray from the light to it.
                const double r = s.radius * 0.999 * std::abs(unit(g)) / len;
                x = s.x + x * r - px, y = s.y + y * r - py, z = s.z + z * r - pz;
                const std::uint32_t* last = nullptr;
                const std::uint32_t* first = grid.list(x, y, z, &last);
                bool found = false;
                for (; first != last; ++first) found = found || *first == i;
                CHECK(found);
            }
    }
}

namespace both_paths {

template <typename C>
long long differing_cells(unsigned seed, long long& listed) {
    std::mt19937 g(seed);
    const int n = 1 + static_cast<int>(g() % 40);
    std::vector<rt::BoundingSphere<C>> spheres;
    spheres.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        spheres.push_back({C(uniform(g, -8, 8)), C(uniform(g, -8, 8)), C(uniform(g, -16, 2)),
                           C(i % 9 == 4 ? 30 : uniform(g, 0.01, 3))});  // some around the light
    std::vector<rt::BoundingSphere<C>> more = spheres;
    for (int i = 0; i < 65; ++i) more.push_back({C(uniform(g, -8, 8)), C(uniform(g, -8, 8)), C(-30), C(0.5)});
    const C x = C(uniform(g, -6, 6)), y = C(uniform(g, -6, 6)), z = C(uniform(g, -12, 2));
    const int cells_per_side = 16;
    const rt::DirectionGrid<C> bits(x, y, z, spheres, cells_per_side);
    const rt::DirectionGrid<C> lists(x, y, z, more, cells_per_side);
    long long differing = 0;
    for (std::int32_t cell = 0; cell < 6 * cells_per_side * cells_per_side; ++cell) {
        const std::uint32_t *last_a, *last_b;
        const std::uint32_t* a = bits.cell_list(cell, &last_a);
        const std::uint32_t* b = lists.cell_list(cell, &last_b);
        std::uint64_t set = 0;
        for (; b != last_b && *b < std::uint32_t(n); ++b, ++a) {
            differing += a == last_a || *a != *b;
            if (a == last_a) break;
            set |= std::uint64_t(1) << *b;
            ++listed;
        }
        differing += a != last_a;
        differing += bits.cell_bits(cell) != set;
    }
    return differing;
}

}  // namespace both_paths

// Up to 64 spheres the lists come from bit sets, beyond that cell by cell: the same
// spheres given alone and followed by 65 more must be listed alike in every cell
// (double and long double).
TEST(bit_set_and_list_grids_list_the_same_spheres) {
    using both_paths::differing_cells;
    long long listed = 0, differing = 0;
    for (unsigned seed = 1; seed <= 60; ++seed) {
        differing += differing_cells<double>(seed, listed);
        differing += differing_cells<long double>(seed, listed);
    }
    CHECK(differing == 0);
    CHECK(listed > 100000);  // many cells list something
}
