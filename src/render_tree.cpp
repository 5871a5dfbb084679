// The tree's path: the reference's shading (whitted.h) a tile at a time
// (whitted_tiles.h), the geometry queries answered by the acceleration layer (bvh.h).
#include "raytracer/render_tree.h"

#include <cstdint>
#include <utility>
#include <vector>

#include "raytracer/accel/bvh.h"
#include "raytracer/accel/whitted_tiles.h"
#include "raytracer/helper_pool.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/render_bands.h"

namespace rt {

namespace {
// A tile's columns: a band of kBandRows rows is a row of tiles (whitted_tiles.h).
constexpr int kTileColumns = 4;
}  // namespace

template <typename Real>
void render_tree_to(const Scene& scene, RowSink& sink, unsigned threads) {
    // The tree is built on the threads asked even for an image of a few rows.
    Bvh<Real> tree(
        scene.spheres.size(), [&scene](std::size_t i) { return make_ellipsoid<Real>(scene.spheres[i]); },
        threads_asked(threads));
    const Whitted<Real, Bvh<Real>> tracer(scene, std::move(tree));
    const WhittedTiles<Real, Bvh<Real>, kBandRows, kTileColumns> tiles(tracer);
    const std::vector<Real> column_x = column_xs<Real>(scene);
    render_bands(
        scene, sink, threads, [&] { return tiles.make_scratch(); },
        [&](int first_row, int rows, std::uint8_t* const* out, auto& scratch) {
            Real band_y[kBandRows] = {};
            for (int j = 0; j < rows; ++j) band_y[j] = tracer.row_y(first_row + j);
            tiles.band(column_x.data(), scene.columns, band_y, out, rows, scratch);
        });
}

// As render.cpp: double for raytracer.exe, float and long double for the tests.
#ifdef RAYTRACER_EXTRA_PRECISIONS
template void render_tree_to<float>(const Scene&, RowSink&, unsigned);
template void render_tree_to<long double>(const Scene&, RowSink&, unsigned);
#else
template void render_tree_to<double>(const Scene&, RowSink&, unsigned);
#endif

}  // namespace rt
