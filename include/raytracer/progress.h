// A progress line for long renders: when stderr is a terminal and the render has run
// past a second, one line kept up to date (percent of rows, elapsed, estimate left),
// erased at the end. A RowSink in front of the real one, so it sees rows as they are
// written, on the writing thread: one clock reading per block of rows (row_ring.h),
// a redraw at most four times a second, no locks, no thread of its own.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

#include "raytracer/row_sink.h"

namespace rt {

// Whether stderr is a terminal (one system call).
bool stderr_is_terminal();

class ProgressSink final : public RowSink {
public:
    // total_bytes: the image's pixel bytes; enabled = false passes rows through only.
    ProgressSink(RowSink& inner, std::size_t total_bytes, bool enabled);
    void rows(const std::uint8_t* bytes, std::size_t size) override;
    // Erases the line, if one was drawn.
    void finish();

    // Nothing is shown before this much time, and redraws are at least this far apart.
    static constexpr std::chrono::milliseconds kFirstAfter{1000}, kRedrawEvery{250};

private:
    void draw(std::chrono::steady_clock::duration elapsed);

    RowSink& inner_;
    const std::size_t total_;
    std::size_t done_ = 0;
    const bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_, next_draw_;
};

}  // namespace rt
