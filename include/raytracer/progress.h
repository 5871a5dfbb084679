// A progress line for long renders: where main() asks for it (by default when stderr is
// a terminal; always with --progress) and the render has run past a second, one line
// kept up to date (percent of rows, elapsed, estimate left), cut to the terminal's
// width so that it never wraps, erased at the end. A RowSink in
// front of the real one, told of finished rows by the thread that writes them, under the
// row ring's lock (row_ring.h), and drawn only when that is the thread that made it: the
// main thread, which the interrupt handlers run on (interrupts.h; not on Windows), so
// that a handler never runs beside a redraw. So the line moves when the main thread
// hands rows over, about once a band of rows of its own, and on the reference path also
// while it renders a row (still_rendering()). One clock reading per call, a redraw at most
// four times a second, no lock and no thread of its own.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <thread>

#include "raytracer/row_sink.h"

namespace rt {

// Whether a standard stream (stdout, stderr) is a terminal (one system call).
bool is_terminal(std::FILE* stream);

class ProgressSink final : public RowSink {
public:
    // enabled = false passes rows through only.
    ProgressSink(RowSink& inner, int total_rows, bool enabled);
    void write_rows(const std::uint8_t* bytes, std::size_t size) override { inner_.write_rows(bytes, size); }
    bool failed() const override { return inner_.failed(); }
    void rows_finished(int count) override;
    void still_rendering() override;
    // Erases the line, if one was drawn.
    void clear_line();

    // Nothing is shown before this much time, and redraws are at least this far apart.
    static constexpr std::chrono::milliseconds kFirstAfter{1000}, kRedrawEvery{250};

private:
    void draw(std::chrono::steady_clock::duration elapsed);

    void erase() const;

    RowSink& inner_;
    const int total_;
    std::atomic<int> done_{0};  // written by the thread that writes, read by the drawer
    const bool enabled_;
    int width_ = 0;  // the longest line that fits the terminal
    int drawn_ = 0;  // the length of the line on the terminal; 0: none
    // The thread that made it, the only one that draws.
    std::thread::id drawer_ = std::this_thread::get_id();
    std::chrono::steady_clock::time_point start_, next_draw_;
};

}  // namespace rt
