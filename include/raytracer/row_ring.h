// The rows of an image on their way to a RowSink while several threads render them: a
// ring of row slots, and the rule for who writes which rows when.
//
// WHY a ring and not the whole image: raytracer.exe only writes the image, row block
// by row block while later rows render, so the rows already written are never read
// again. Each 4 KiB of fresh memory costs a page fault (1-13 us on the virtual machines
// of docs/speed.md): a 400x400 image is 118 pages, the ring of two 64 KiB write blocks 32.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>

#include "raytracer/image.h"
#include "raytracer/row_sink.h"

namespace rt {

// Rows are rendered in bands taken in increasing order from a shared counter; for
// each band a thread calls reserve(end), writes its rows through row(r), and then
// finish(r) for each. Once every row is finished, the caller calls flush(). The sink
// gets every row exactly once, in order, in whole rows, one call at a time.
//
// A band waits in reserve() only while the rows a ring earlier are not yet written (a
// thread stalled on an early band, or a write the sink holds up); the waiting thread
// writes what it can meanwhile, and sleeps while another thread writes.
// The wait always ends: the oldest band being rendered never waits (every row before
// it is finished, so it can write up to its first row), and the later ones wait only
// for older ones.
class RowRing {
public:
    // rows of row_bytes bytes each; bands of at most band_rows rows, rendered by at
    // most threads threads at once.
    RowRing(RowSink& sink, int rows, std::size_t row_bytes, int band_rows, unsigned threads);

    // Once this returns, the slots of the rows before end may be used: every row at
    // least a ring before end is written.
    void reserve(int end);
    // Row r's bytes, row_bytes of them; not initialised. Valid from reserve() past r
    // until finish(r).
    std::uint8_t* row(int r) { return slots_.data() + static_cast<std::size_t>(r % ring_rows_) * row_bytes_; }
    // Row r is complete: gives the sink a block of finished rows when one is ready and
    // no other thread is writing (a thread never waits here to write).
    void finish(int r);
    // After every row is finished: gives the sink the rest.
    void flush();

    // Whether the sink takes no more bytes (RowSink::failed()): the rows still to come
    // need not be drawn.
    bool sink_failed() const { return sink_.failed(); }
    int ring_rows() const { return ring_rows_; }
    int block_rows() const { return block_rows_; }

    // The sink gets blocks of at least this many bytes, or of one row where a row is
    // larger: fewer, larger writes. Smaller only at the end, where the ring wraps, and
    // while a thread waits for slots. WHY 64 KiB: 32 and 16 KiB, with rings to match,
    // were slower (testIllum at 400x400, medians of 300: 2.21, 2.25, 2.28 ms).
    static constexpr std::size_t kBlockBytes = std::size_t{1} << 16;
    // The ring also holds at least this many bands per thread (at large widths a
    // block is only a row or two).
    static constexpr int kBandsPerThread = 8;

private:
    // Gives the sink the finished rows from rows_written_ on, if at least at_least of them.
    // Under writing_.
    void hand_over(int at_least);

    RowSink& sink_;
    const int rows_;
    const std::size_t row_bytes_;
    const int block_rows_, ring_rows_;
    Bytes slots_;  // ring_rows_ rows; row r in slot r % ring_rows_
    const std::unique_ptr<std::atomic<bool>[]> finished_;
    std::mutex writing_;
    // Rows given to the sink: changed under writing_, read by threads waiting for slots.
    std::atomic<int> rows_written_{0};
};

}  // namespace rt
