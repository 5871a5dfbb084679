// Renders a scene to an image: one eye ray per pixel through the pixel's top-left
// corner on the near plane (SPEC section 3), traced in the scalar type Real.
#pragma once

#include "raytracer/image.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// The number of threads render() uses by default: all cores.
unsigned default_thread_count();

// Instantiated for float, double and long double (src/render.cpp). threads = 0 means
// default_thread_count(); the image is byte-identical for any number of threads.
// accelerate = false renders without any shortcut (see Tracer), for tests. A sink, when
// given, receives every row of the image, in order, before render() returns: most of
// them while later rows are still being rendered (so that writing a file overlaps the
// render).
template <typename Real>
Image render(const Scene& scene, unsigned threads = 0, bool accelerate = true, RowSink* sink = nullptr);

}  // namespace rt
