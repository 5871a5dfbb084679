// Renders through the reference path (whitted.h), each pixel on its own, rows shared by
// the threads: with the acceleration layer (bvh.h), as render_to() does for scenes
// beyond the flat sweep's size (takes_the_tree()), or with brute force, the reference.
#pragma once

#include <cstddef>

#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// Up to this many ellipsoids the flat sweep (tracer.h: every ellipsoid culled by its
// bounding sphere, hits shaded in vector packets) is faster than this path's scalar
// rays through the tree. Whole process, one thread, CPU time, medians of 5: random
// scenes (scale_scenes.h) of 300 / 500 / 700 / 1,000 ellipsoids 0.03 / 0.04 / 0.06 /
// 0.07 s flat against 0.07 / 0.09 / 0.10 / 0.10 s here; sphereflake level 3 (821)
// 0.07 s flat against 0.05 s here; past a few thousand the flat sweep's tables stop at
// their limits and it is many times slower (random 4,000: 3.9 s).
inline constexpr std::size_t kFlatSweepEllipsoids = 512;
// and while ellipsoids x lights stay below this: the flat sweep keeps tables per
// ellipsoid and light (about 100 bytes a pair), this path nothing per pair.
inline constexpr std::size_t kFlatSweepPairs = 65536;

// Whether render_to() takes this path for the scene.
inline bool takes_the_tree(std::size_t ellipsoids, std::size_t lights) {
    return ellipsoids > kFlatSweepEllipsoids || ellipsoids * lights > kFlatSweepPairs;
}

// Instantiated for float, double and long double; threads = 0: all cores.
template <typename Real>
void render_whitted_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

// The same with BruteForce (every ray against every ellipsoid): the reference, the
// specification in code, that render(..., accelerate = false) makes and the tests hold
// every other path to, byte for byte.
template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

}  // namespace rt
