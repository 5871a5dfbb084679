// The light buffers' cell lists (DirectionGrid) are built two ways: up to 64 spheres as
// bit sets, sphere by sphere over each face's cells (a vector loop), beyond that cell by
// cell as lists. Both must list exactly the same spheres in every cell: here the same
// spheres are given once alone and once followed by 65 more (which forces the list
// path), and every cell's list, and its bit set, must agree on the first ones.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "check.h"
#include "raytracer/direction_grid.h"

namespace {

double uniform(std::mt19937& g, double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(g()) / 4294967296.0);
}

template <typename C>
long long differing_cells(unsigned seed, long long& listed) {
    std::mt19937 g(seed);
    const int n = 1 + static_cast<int>(g() % 40);
    std::vector<rt::BoundingSphere<C>> spheres;
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

}  // namespace

TEST(bit_set_and_list_grids_list_the_same_spheres) {
    long long listed = 0, differing = 0;
    for (unsigned seed = 1; seed <= 60; ++seed) {
        differing += differing_cells<double>(seed, listed);
        differing += differing_cells<long double>(seed, listed);
    }
    CHECK(differing == 0);
    CHECK(listed > 100000);  // many cells list something
}
