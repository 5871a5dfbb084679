// The row ring's promises (row_ring.h): the sink gets every row once, in order, in
// whole rows and blocks, one call at a time, whichever threads render which bands in
// whatever order they finish; a band never reuses the slot of a row not yet written.
// And render_bands(), the loop over it that every path runs.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "check.h"
#include "raytracer/render_bands.h"
#include "raytracer/row_ring.h"
#include "raytracer/scene.h"

namespace {

// Row r's bytes in these tests: its number and the column, so that a row written into
// the wrong slot, twice or not at all shows in the sink's bytes.
std::uint8_t byte_of(int row, std::size_t i) {
    return static_cast<std::uint8_t>(row * 7 + static_cast<int>(i));
}

void fill(rt::RowRing& ring, int row, std::size_t row_bytes) {
    std::uint8_t* out = ring.row(row);
    for (std::size_t i = 0; i < row_bytes; ++i) out[i] = byte_of(row, i);
}

std::vector<std::uint8_t> expected(int rows, std::size_t row_bytes) {
    std::vector<std::uint8_t> all;
    for (int r = 0; r < rows; ++r)
        for (std::size_t i = 0; i < row_bytes; ++i) all.push_back(byte_of(r, i));
    return all;
}

// Records the calls; notes a call that overlaps another.
struct Sink final : rt::RowSink {
    std::vector<std::uint8_t> bytes;
    std::vector<std::size_t> sizes;
    std::atomic<int> inside{0};
    bool overlapped = false;
    void write_rows(const std::uint8_t* data, std::size_t size) override {
        if (inside.fetch_add(1) != 0) overlapped = true;
        bytes.insert(bytes.end(), data, data + size);
        sizes.push_back(size);
        inside.fetch_sub(1);
    }
};

// Renders rows bands of band_rows from a shared counter on `threads` threads, as
// render_to() does; delay(band) is spent between reserve() and finish().
template <typename Delay>
void render(rt::RowRing& ring, int rows, std::size_t row_bytes, int band_rows, unsigned threads,
            Delay delay) {
    std::atomic<int> next{0};
    auto work = [&] {
        for (int r = next.fetch_add(band_rows); r < rows; r = next.fetch_add(band_rows)) {
            const int end = std::min(r + band_rows, rows);
            ring.reserve(end);
            delay(r / band_rows);
            for (int f = r; f < end; ++f) fill(ring, f, row_bytes);
            for (int f = r; f < end; ++f) ring.finish(f);
        }
    };
    std::vector<std::thread> helpers;
    for (unsigned t = 1; t < threads; ++t) helpers.emplace_back(work);
    work();
    for (std::thread& t : helpers) t.join();
    ring.flush();
}

}  // namespace

TEST(sizes_follow_the_block_and_the_bands) {
    Sink sink;
    // 400 columns: 54 rows of 1200 bytes in 64 KiB; two blocks beat 8 bands of 4 per thread.
    CHECK_EQ(rt::RowRing(sink, 400, 1200, 4, 2).block_rows(), 54);
    CHECK_EQ(rt::RowRing(sink, 400, 1200, 4, 2).ring_rows(), 108);
    CHECK_EQ(rt::RowRing(sink, 400, 1200, 4, 8).ring_rows(), 256);  // 8 threads: 4 x 8 x 8 rows
    CHECK_EQ(rt::RowRing(sink, 50, 1200, 4, 2).ring_rows(), 50);    // never more than the image
    // Rows wider than a block: a block is one row, the ring the bands.
    CHECK_EQ(rt::RowRing(sink, 4320, std::size_t{7680} * 3, 4, 2).block_rows(), 2);
    CHECK_EQ(rt::RowRing(sink, 4320, std::size_t{7680} * 3, 4, 2).ring_rows(), 64);
    CHECK_EQ(rt::RowRing(sink, 1, 100000, 4, 64).ring_rows(), 1);
}

TEST(one_thread_gives_whole_blocks_in_order) {
    const int rows = 400;
    const std::size_t row_bytes = 1200;
    Sink sink;
    rt::RowRing ring(sink, rows, row_bytes, 4, 1);
    render(ring, rows, row_bytes, 4, 1, [](int) {});
    CHECK(sink.bytes == expected(rows, row_bytes));
    // Rows finish in order, so each block is written as soon as it is whole: 7 blocks
    // of 54 rows (the ring of 108 holds two, so none is cut where it wraps), then the
    // last 22 rows.
    CHECK_EQ(sink.sizes.size(), std::size_t{8});
    for (std::size_t i = 0; i < sink.sizes.size(); ++i)
        CHECK_EQ(sink.sizes[i], (i + 1 < sink.sizes.size() ? 54 : 22) * row_bytes);
}

TEST(threads_in_any_order_give_every_row_once_in_order) {
    const std::size_t row_bytes = 300;
    for (unsigned threads : {2U, 3U, 8U}) {
        for (int rows : {1, 5, 217, 1000}) {
            Sink sink;
            rt::RowRing ring(sink, rows, row_bytes, 4, threads);
            // Uneven bands: every seventh sleeps a little, so that later bands finish first.
            render(ring, rows, row_bytes, 4, threads, [](int band) {
                if (band % 7 == 3) std::this_thread::sleep_for(std::chrono::microseconds(200));
            });
            CHECK(sink.bytes == expected(rows, row_bytes));
            CHECK(!sink.overlapped);
            for (std::size_t size : sink.sizes) CHECK(size > 0 && size % row_bytes == 0);
        }
    }
}

// A band held up long: the other threads render until the ring is full, then wait for
// it, and no band past the ring starts before it is finished.
TEST(bands_past_the_ring_wait_for_a_stalled_band) {
    const int rows = 600;
    const std::size_t row_bytes = 1200;
    Sink sink;
    rt::RowRing ring(sink, rows, row_bytes, 4, 2);
    std::atomic<bool> first_done{false};
    std::atomic<int> early{0};  // bands past the ring that started while band 0 was held
    std::atomic<int> next{0};
    auto work = [&] {
        for (int r = next.fetch_add(4); r < rows; r = next.fetch_add(4)) {
            const int end = std::min(r + 4, rows);
            ring.reserve(end);
            if (r == 0) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            } else if (end > ring.ring_rows() && !first_done.load()) {
                ++early;
            }
            for (int f = r; f < end; ++f) fill(ring, f, row_bytes);
            if (r == 0) first_done.store(true);
            for (int f = r; f < end; ++f) ring.finish(f);
        }
    };
    std::thread helper(work);
    work();
    helper.join();
    ring.flush();
    CHECK_EQ(early.load(), 0);
    CHECK(sink.bytes == expected(rows, row_bytes));
}

// render_bands() (render_bands.h), the loop over the ring that every path runs: every
// row drawn once and given in order, and never more threads than bands, however many
// are asked for (another would hold its scratch, a band's worth of memory, and draw
// nothing: 1,024 threads on an image 100,000 wide held 6.5 GB).
TEST(render_bands_draws_every_row_once_on_no_more_threads_than_bands) {
    rt::Scene scene;
    scene.columns = 5;
    scene.rows = 9;  // 3 bands of 4 rows
    const std::size_t row_bytes = rt::bytes_of_pixels(scene.columns);
    for (const unsigned threads : {1U, 2U, 64U}) {
        Sink sink;
        std::atomic<int> scratches{0};
        rt::render_bands(
            scene, sink, threads, [&] { return scratches.fetch_add(1); },
            [&](int first_row, int rows, std::uint8_t* const* out, int&) {
                for (int j = 0; j < rows; ++j)
                    for (std::size_t i = 0; i < row_bytes; ++i) out[j][i] = byte_of(first_row + j, i);
            });
        CHECK(sink.bytes == expected(scene.rows, row_bytes));
        CHECK(scratches.load() <= 3);
    }
}
