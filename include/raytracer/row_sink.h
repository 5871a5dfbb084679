// Where render_to() hands an image's bytes while it is still rendering them, and
// ImageSink, which collects them into an image.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raytracer/image.h"

namespace rt {

// Receives an image's bytes in order, whole rows at a time, exactly once each: the
// concatenation of all calls is the image's rgb. Called from any of the render's
// threads, one call at a time; must not throw.
class RowSink {
public:
    virtual void write_rows(const std::uint8_t* bytes, std::size_t size) = 0;
    // The first count rows are finished (perhaps not yet given to write_rows()): for a progress
    // display. Called by the thread that writes, under the same rule as write_rows(), as often
    // as once per finished row; the default does nothing.
    virtual void rows_finished(int count) { (void)count; }
    // A thread rendering a long row (the reference path, every few pixels): for a
    // progress display that would otherwise wait for the row's end. Called by any of the
    // render's threads at any time, beside any other call; the default does nothing.
    virtual void still_rendering() {}
    // Whether the sink takes no more bytes (a write failed): the rows still to come are
    // then not drawn, only counted through (render_bands.h, render_flat_sweep.cpp), so a
    // full disk ends the run at once rather than after the whole render. Called by any
    // of the render's threads at any time; the default is false.
    virtual bool failed() const { return false; }

protected:
    RowSink() = default;
    RowSink(const RowSink&) = default;
    RowSink& operator=(const RowSink&) = default;
    ~RowSink() = default;
};

// The simplest sink: the rows collected into an image of width x height.
struct ImageSink final : RowSink {
    Image image;
    ImageSink(int width, int height) {
        image.width = width, image.height = height;
        image.rgb.reserve(bytes_of_pixels(width, height));
    }
    void write_rows(const std::uint8_t* bytes, std::size_t size) override {
        image.rgb.insert(image.rgb.end(), bytes, bytes + size);
    }
};

}  // namespace rt
