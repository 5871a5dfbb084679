// Renders through the reference path (whitted.h), rows shared by the threads: with the
// acceleration layer (bvh.h) a tile at a time, as render_to() does for scenes beyond the
// flat sweep's range (takes_the_tree()), or each pixel with brute force, the reference.
#pragma once

#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// Instantiated for float, double and long double; threads = 0: all cores.
template <typename Real>
void render_whitted_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

// The same with BruteForce (every ray against every ellipsoid): the reference, the
// specification in code, that render(..., accelerate = false) makes and the tests hold
// every other path to, byte for byte.
template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

}  // namespace rt
