// The loop that every path shares: the image's rows in bands of a few, taken from a
// shared counter by each thread, so that a thread that draws cheap rows takes more of
// them; the rows go to the sink in order as they are finished (row_ring.h), and the
// helper threads are called in at the start or once they pay.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>

#include "raytracer/helper_pool.h"
#include "raytracer/image.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/row_ring.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// The rows a band holds (the tree's tiles are this many rows high).
constexpr int kBandRows = 4;

// When a render on all cores (threads = 0) calls in its helpers.
enum class CallHelpers {
    AtStart,
    // Once the rest of the image would take the calling thread longer than
    // worth_helping() alone, at its pace so far: an image done sooner never calls them.
    WhenWorthIt,
    // Never: for an image whose rows are copies of the background, which go to the sink
    // one write at a time, so that a helper would only wait its turn.
    Never,
};

// Calling a helper costs the calling thread about 0.08 ms. Where it starts on an idle
// core at once (helper_pool.h) it draws rows about 0.1 ms later, and the earlier the
// call, the more of the image it shares (100 us rather than 400 us took 0.1 to 0.2 ms
// off testIllum, testReflection, testAmbient and testShadow at 400x400, whole process,
// medians of 21 to 25 interleaved runs); where it waits for the scheduler to move it,
// 3 ms later.
inline std::chrono::microseconds worth_helping() {
    return std::chrono::microseconds(HelperPool::starts_on_idle_core() ? 100 : 3000);
}

// The image on `threads` threads (0: all cores, called in as `when` says; never more
// than one a band, as another would hold its scratch and draw nothing): each band of at
// most BandRows rows drawn by draw(first_row, rows, out, scratch), out[j] the bytes of
// row first_row + j, with the drawing thread's scratch from make_scratch(). Every pixel
// must be a pure function of the scene and its position, so that the image is the same
// whichever thread draws which rows.
template <int BandRows = kBandRows, typename MakeScratch, typename Draw>
void render_bands(const Scene& scene, RowSink& sink, unsigned threads, MakeScratch make_scratch, Draw draw,
                  CallHelpers when = CallHelpers::AtStart) {
    const int bands = scene.rows / BandRows + (scene.rows % BandRows != 0 ? 1 : 0);
    const unsigned most = std::min(threads_asked(threads), static_cast<unsigned>(std::max(1, bands)));
    RowRing ring(sink, scene.rows, bytes_of_pixels(scene.columns), BandRows, most);
    std::atomic<int> next_row{0};
    using Scratch = decltype(make_scratch());
    // Takes bands until none is left; after_band(end) after each, rows [0, end) drawn or taken.
    auto take_bands = [&](Scratch& scratch, auto after_band) {
        for (int r = next_row.fetch_add(BandRows); r < scene.rows; r = next_row.fetch_add(BandRows)) {
            const int end = std::min(r + BandRows, scene.rows);
            ring.reserve(end);
            std::uint8_t* out[BandRows] = {};
            for (int row = r; row < end; ++row) out[row - r] = ring.row(row);
            if (!ring.sink_failed()) draw(r, end - r, out, scratch);
            for (int row = r; row < end; ++row) ring.finish(row);
            after_band(end);
        }
    };
    // Each helper's scratch is made on this thread, so that a helper thread allocates
    // nothing (its first allocation would set up a malloc arena of its own).
    OwnLinesVector<Scratch> helper_scratch;
    auto help = [&](unsigned h) { take_bands(helper_scratch[h], [](int) {}); };
    HelperPool::Job helpers;  // declared after all that help uses: closed first
    auto call_helpers = [&](unsigned count) {
        helper_scratch.reserve(count - 1);  // no reallocation: the helpers hold references
        for (unsigned h = 0; h + 1 < count; ++h) helper_scratch.push_back(make_scratch());
        helpers.start(count - 1, help);
    };
    if (most > 1 && (threads > 1 || when == CallHelpers::AtStart)) call_helpers(most);
    bool decided = threads != 0 || when != CallHelpers::WhenWorthIt;  // asked for, judged, or of no use
    Scratch scratch = make_scratch();
    const auto start = std::chrono::steady_clock::now();
    const auto worth = worth_helping();
    take_bands(scratch, [&](int done) {
        if (decided) return;
        // Not judged on its first eighth of worth_helping() (cold caches).
        const int left = scene.rows - done;
        const auto elapsed = std::chrono::steady_clock::now() - start;
        if (left > 0 && elapsed * 8 >= worth && elapsed * left >= worth * done) {
            decided = true;
            if (most > 1) call_helpers(std::min(most, static_cast<unsigned>(left + 1)));
        }
    });
    helpers.finish();
    ring.flush();
}

}  // namespace rt
