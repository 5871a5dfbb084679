// Renders through the reference path (whitted.h) with the acceleration layer (bvh.h):
// each pixel on its own, rows shared by the threads. render_to() takes this path for
// scenes beyond the flat sweep's size (kFlatSweepEllipsoids); the image is the one the
// plain tracer makes, byte for byte.
#pragma once

#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// Past this many ellipsoids the flat sweep's shortcuts (64-bit ellipsoid sets, tables
// per ellipsoid and light) no longer hold, and the tree is faster.
inline constexpr std::size_t kFlatSweepEllipsoids = 64;

// Instantiated for float, double and long double; threads = 0: all cores.
template <typename Real>
void render_whitted_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

}  // namespace rt
