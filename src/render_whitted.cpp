#include "raytracer/render_whitted.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "raytracer/accel/bvh.h"
#include "raytracer/accel/whitted_tiles.h"
#include "raytracer/helper_pool.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/render.h"
#include "raytracer/row_ring.h"

namespace rt {

namespace {
// The threads a render uses: as asked, at most one per row.
unsigned thread_count(const Scene& scene, unsigned threads) {
    return std::min<unsigned>(threads_asked(threads), static_cast<unsigned>(scene.rows));
}

// Bands of a few rows from a shared counter, so that a thread that draws cheap rows
// takes more of them; the rows go to the sink from a ring as they are finished.
constexpr int kBandRows = 4;
// A tile: kBandRows rows by kTileColumns columns, traced together (whitted_tiles.h).
constexpr int kTileColumns = 4;

// What the pixel by pixel path has in place of tiles.
struct Nothing {
    template <typename Tracer>
    explicit Nothing(const Tracer& /*unused*/) {}
};

// The image through Whitted<Real, Geometry> on count threads, rows shared: each pixel on
// its own, or where kTiles a tile at a time (the same bytes).
template <bool kTiles, typename Real, typename Geometry>
void render_pixels_to(const Scene& scene, Geometry geometry, RowSink& sink, unsigned count) {
    const Whitted<Real, Geometry> tracer(scene, std::move(geometry));
    using Tiles = std::conditional_t<kTiles, WhittedTiles<kBandRows * kTileColumns, Real, Geometry>, Nothing>;
    const Tiles tiles(tracer);
    const std::size_t row_bytes = static_cast<std::size_t>(scene.columns) * 3;
    RowRing ring(sink, scene.rows, row_bytes, kBandRows, count);
    std::vector<Real> column_x(static_cast<std::size_t>(scene.columns));
    for (int c = 0; c < scene.columns; ++c) column_x[static_cast<std::size_t>(c)] = tracer.column_x(c);

    // Every pixel is a pure function of the scene and its (column, row), so the image is
    // the same whichever thread renders which rows.
    std::atomic<int> next_row{0};
    auto take_rows = [&]() {
        auto scratch = [&] {
            if constexpr (kTiles)
                return tiles.make_scratch();
            else
                return tracer.make_scratch();
        }();
        for (int r = next_row.fetch_add(kBandRows); r < scene.rows; r = next_row.fetch_add(kBandRows)) {
            const int end = std::min(r + kBandRows, scene.rows);
            ring.reserve(end);
            if constexpr (kTiles) {
                static_assert(Tiles::kRows == kBandRows, "a band is a row of tiles");
                Real band_y[kBandRows] = {};
                std::uint8_t* band_out[kBandRows] = {};
                for (int row = r; row < end; ++row)
                    band_y[row - r] = tracer.row_y(row), band_out[row - r] = ring.row(row);
                tiles.band(column_x.data(), scene.columns, band_y, band_out, end - r, scratch);
            } else {
                for (int row = r; row < end; ++row) {
                    std::uint8_t* const out = ring.row(row);
                    const Real y = tracer.row_y(row);
                    for (std::size_t c = 0; c < column_x.size(); ++c)
                        tracer.pixel(column_x[c], y, out + c * 3, scratch);
                }
            }
            for (int row = r; row < end; ++row) ring.finish(row);
        }
    };
    HelperPool::Job helpers;
    if (count > 1) helpers.start(count - 1, take_rows);
    take_rows();
    helpers.finish();
    ring.flush();
}
}  // namespace

template <typename Real>
void render_whitted_to(const Scene& scene, RowSink& sink, unsigned threads) {
    // The tree is built on the threads asked even for an image of a few rows.
    Bvh<Real> tree(
        scene.spheres.size(), [&scene](std::size_t i) { return make_ellipsoid<Real>(scene.spheres[i]); },
        threads_asked(threads));
    render_pixels_to<true, Real>(scene, std::move(tree), sink, thread_count(scene, threads));
}

template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads) {
    render_pixels_to<false, Real>(scene, BruteForce<Real>(make_ellipsoids<Real>(scene)), sink,
                                  thread_count(scene, threads));
}

// As in render.cpp: double for raytracer.exe, float and long double for the tests.
#ifdef RAYTRACER_EXTRA_PRECISIONS
template void render_whitted_to<float>(const Scene&, RowSink&, unsigned);
template void render_whitted_to<long double>(const Scene&, RowSink&, unsigned);
template void render_reference_to<float>(const Scene&, RowSink&, unsigned);
template void render_reference_to<long double>(const Scene&, RowSink&, unsigned);
#else
template void render_whitted_to<double>(const Scene&, RowSink&, unsigned);
template void render_reference_to<double>(const Scene&, RowSink&, unsigned);
#endif

}  // namespace rt
