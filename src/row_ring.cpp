#include "raytracer/row_ring.h"

#include <algorithm>
#include <thread>

namespace rt {

namespace {

int rows_per_block(std::size_t row_bytes) {
    return static_cast<int>(
        std::max<std::size_t>(1, RowRing::kBlockBytes / std::max<std::size_t>(1, row_bytes)));
}

// Two write blocks (one is rendered while the other is written) and at least
// kBandsPerThread bands per thread; never more than the image.
int ring_size(int rows, int block_rows, int band_rows, unsigned threads) {
    const std::size_t bands =
        std::size_t(std::max(1, band_rows)) * RowRing::kBandsPerThread * std::max(1U, threads);
    return static_cast<int>(std::min<std::size_t>(std::size_t(std::max(1, rows)),
                                                  std::max<std::size_t>(2 * std::size_t(block_rows), bands)));
}

}  // namespace

RowRing::RowRing(RowSink& sink, int rows, std::size_t row_bytes, int band_rows, unsigned threads)
    : sink_(sink),
      rows_(rows),
      row_bytes_(row_bytes),
      block_rows_(rows_per_block(row_bytes)),
      ring_rows_(ring_size(rows, block_rows_, band_rows, threads)),
      slots_(row_bytes * static_cast<std::size_t>(ring_rows_)),
      finished_(new std::atomic<bool>[static_cast<std::size_t>(std::max(1, rows))]()) {}

void RowRing::hand_over(int at_least) {
    int from = rows_written_.load(std::memory_order_relaxed), end = from;
    while (end < rows_ && finished_[static_cast<std::size_t>(end)].load(std::memory_order_acquire)) ++end;
    sink_.rows_finished(end);
    if (end - from < std::max(1, at_least)) return;
    while (from < end) {  // in one piece, or two where the ring wraps
        const int to = std::min(end, (from / ring_rows_ + 1) * ring_rows_);
        sink_.write_rows(row(from), static_cast<std::size_t>(to - from) * row_bytes_);
        from = to;
    }
    rows_written_.store(end, std::memory_order_release);  // their slots are free
}

void RowRing::reserve(int end) {
    while (end - rows_written_.load(std::memory_order_acquire) > ring_rows_) {
        {
            // Where another thread is writing, this one sleeps until it is done: that
            // write may wait long on a slow reader of a pipe.
            const std::lock_guard<std::mutex> lock(writing_);
            hand_over(1);
        }
        // The rows before are not all finished: an older band is still being rendered.
        if (end - rows_written_.load(std::memory_order_acquire) > ring_rows_) std::this_thread::yield();
    }
}

void RowRing::finish(int r) {
    finished_[static_cast<std::size_t>(r)].store(true, std::memory_order_release);
    if (!writing_.try_lock()) return;  // another thread is writing: it or a later row sends this one
    hand_over(block_rows_);
    writing_.unlock();
}

void RowRing::flush() {
    const std::lock_guard<std::mutex> lock(writing_);
    hand_over(1);
}

}  // namespace rt
