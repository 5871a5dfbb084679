// The flat sweep: every ellipsoid culled by its bounding sphere, eye rays by row, hits
// shaded in vector packets (packet_tracer.h and the headers beside it). It renders the bytes
// of the reference path (whitted.h) faster up to 200 ellipsoids, and render_to() takes
// it within the range below; the tree (bvh.h) takes every other scene.
#pragma once

#include <cstddef>
#include <type_traits>

#include "raytracer/row_sink.h"
#include "raytracer/scene.h"
#include "raytracer/scene_precision.h"

namespace rt {

// Up to this many ellipsoids the flat sweep renders: about where the tree overtakes it. Whole process,
// 2 threads, wall, interleaved, medians of 15 (2026-12-03 12:10 UTC): random scenes (scale_scenes.h) of
// 150 / 200 / 256 / 300 ellipsoids 9.7 / 13.6 / 18.5 / 21.7 ms flat against 12.7 / 15.5 / 16.7 / 16.8 ms
// in the tree; the first 150 / 200 / 256 / 300 of sphereflake 3 (mirrors) 8.8 / 10.2 / 13.2 / 17.1 ms
// flat against 12.0 / 12.7 / 13.5 / 16.3 ms. Where the tiles' lanes are arrays (no AVX: lanes.h) the
// tree overtakes it there too (x86-64-v2, rendering alone, 2 threads, medians of 9, 2026-12-05: the
// tree took 1.02 / 0.95 / 0.88 / 0.79 times the flat sweep's time on random 200 / 250 / 300 / 384, and
// 0.95 / 0.86 / 0.77 / 0.67 times on the first 200 / 250 / 300 / 384 of sphereflake 3).
inline constexpr std::size_t kFlatSweepEllipsoids = 200;
// and while ellipsoids x lights stay at most this: the flat sweep keeps a light cone per
// ellipsoid and light (light_cones.h), the tree one blocker hint per pair in a table of
// at most 4 MiB (blocker_hints.h). Within it,
// 200 random ellipsoids with 240 / 320 lights took 203 / 270 ms flat against 237 / 309 ms
// in the tree, 128 with 500 227 against 320 ms (400x400, whole process, medians of 5).
inline constexpr std::size_t kFlatSweepPairs = 65536;

// The flat sweep's shortcuts multiply squared lengths (4th powers of the scene's
// numbers), which overflow or underflow past about 1e+-77: they are exact while every
// length of the scene lies within [1e-60, 1e60] or is 0 (measured: scenes scaled by
// 1e+-80 rendered exactly, by 1e+-90 did not). The tree is exact at any scale.
inline constexpr double kFlatSweepSmallest = 1e-60, kFlatSweepLargest = 1e60;

// Whether every length of the scene (its window, centres, scales and lights) is within
// the flat sweep's range.
bool lengths_fit_the_flat_sweep(const Scene& scene);

// Whether the scene lies past the flat sweep's range, so that render_to() takes the tree
// without asking the flat sweep (which may still decline a scene within it).
inline bool takes_the_tree(const Scene& scene) {
    const std::size_t ellipsoids = scene.spheres.size();
    return ellipsoids > kFlatSweepEllipsoids || ellipsoids * scene.lights.size() > kFlatSweepPairs ||
           !lengths_fit_the_flat_sweep(scene);
}

// The precisions the flat sweep renders in: double, and long double where it is wider
// than double. Its shortcuts compute in the scene's own type, and their margins need
// double's rounding at least (shadow_prefilter.h).
template <typename Real>
inline constexpr bool kFlatSweepPrecision = std::is_same_v<AtLeastDouble<Real>, Real>;

// The image through the flat sweep, or false with nothing rendered where it declines: a
// precision it does not render in, or a scene where its packets would not pay
// (PacketTracer::can_render()). Instantiated for double in raytracer.exe, for float and
// long double in raytracer_precisions (render.cpp); threads = 0: see render_to().
template <typename Real>
bool render_flat_sweep_to(const Scene& scene, RowSink& sink, unsigned threads);

}  // namespace rt
