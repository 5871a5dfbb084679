// Renders a scene to an image: one eye ray per pixel through the pixel's top-left
// corner on the near plane (SPEC section 3), traced in the scalar type Real.
#pragma once

#include "raytracer/image.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// The threads a render is asked for: `threads`, or all cores where it is 0.
unsigned threads_asked(unsigned threads);

// Instantiated for float, double and long double (src/render.cpp). threads = 0 means
// all cores (threads_asked()); the image is byte-identical for any number of threads.
// accelerate = false renders through the reference path (whitted.h with brute_force.h:
// every ray against every ellipsoid), which the tests hold the fast paths to.
template <typename Real>
Image render(const Scene& scene, unsigned threads = 0, bool accelerate = true);

// Renders as render() does, but hands the image's rows to sink as they are finished
// (so that writing a file overlaps the render) and never holds the whole image: every
// row reaches sink, in order, before render_to() returns.
template <typename Real>
void render_to(const Scene& scene, RowSink& sink, unsigned threads = 0, bool accelerate = true);

}  // namespace rt
