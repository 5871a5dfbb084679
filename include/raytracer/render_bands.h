// The loop that the reference path and the tree share: the image's rows in bands of a
// few, taken from a shared counter by each thread, so that a thread that draws cheap
// rows takes more of them; the rows go to the sink in order as they are finished.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "raytracer/helper_pool.h"
#include "raytracer/image.h"
#include "raytracer/row_ring.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// The rows a band holds (the tree's tiles are this many rows high).
constexpr int kBandRows = 4;

// The image on `threads` threads (0: all cores; never more than one a row): each band
// drawn by draw(first_row, rows, out, scratch), out[j] the bytes of row first_row + j,
// with the drawing thread's scratch from make_scratch(). Every pixel must be a pure
// function of the scene and its position, so that the image is the same whichever
// thread draws which rows.
template <typename MakeScratch, typename Draw>
void render_bands(const Scene& scene, RowSink& sink, unsigned threads, MakeScratch make_scratch, Draw draw) {
    const unsigned count = std::min<unsigned>(threads_asked(threads), static_cast<unsigned>(scene.rows));
    RowRing ring(sink, scene.rows, bytes_of_pixels(scene.columns), kBandRows, count);
    std::atomic<int> next_row{0};
    auto take_bands = [&]() {
        auto scratch = make_scratch();
        for (int r = next_row.fetch_add(kBandRows); r < scene.rows; r = next_row.fetch_add(kBandRows)) {
            const int end = std::min(r + kBandRows, scene.rows);
            ring.reserve(end);
            std::uint8_t* out[kBandRows] = {};
            for (int row = r; row < end; ++row) out[row - r] = ring.row(row);
            if (!ring.sink_failed()) draw(r, end - r, out, scratch);
            for (int row = r; row < end; ++row) ring.finish(row);
        }
    };
    HelperPool::Job helpers;
    if (count > 1) helpers.start(count - 1, take_bands);
    take_bands();
    helpers.finish();
    ring.flush();
}

}  // namespace rt
