// Where render() can hand an image's bytes while it is still rendering them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rt {

// Receives an image's bytes in order, whole rows at a time, exactly once each: the
// concatenation of all calls is the image's rgb. Called from any of the render's
// threads, one call at a time; must not throw.
class RowSink {
public:
    virtual void rows(const std::uint8_t* bytes, std::size_t size) = 0;
    // The first count rows are finished (perhaps not yet given to rows()): for a progress
    // display. Called by the thread that writes, under the same rule as rows(), as often
    // as once per finished row; the default does nothing.
    virtual void rows_finished(int count) { (void)count; }

protected:
    RowSink() = default;
    RowSink(const RowSink&) = default;
    RowSink& operator=(const RowSink&) = default;
    ~RowSink() = default;
};

}  // namespace rt
