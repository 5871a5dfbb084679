// Renders a scene to an image: one eye ray per pixel through the pixel's top-left
// corner on the near plane (SPEC section 3), traced in the scalar type Real: double in
// raytracer.exe, float and long double too for the tests (src/render.cpp,
// src/render_reference.cpp); threads = 0 means all cores, and the image is
// byte-identical for any number of threads.
#pragma once

#include <utility>

#include "raytracer/image.h"
#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// The fast path, raytracer.exe's: the flat sweep up to 200 ellipsoids, the tree past
// them (exactly where: takes_the_tree() and PacketTracer::can_render(); docs/speed.md). It hands the image's
// rows to sink as they are finished (so that writing a file overlaps the render) and never holds the whole
// image: every row reaches sink, in order, before render_to() returns.
template <typename Real>
void render_to(const Scene& scene, RowSink& sink, unsigned threads = 0);
// The same, the image returned whole.
template <typename Real>
Image render(const Scene& scene, unsigned threads = 0) {
    ImageSink sink(scene.columns, scene.rows);
    render_to<Real>(scene, sink, threads);
    return std::move(sink.image);
}

// The reference path, the specification in code: each pixel on its own through
// reference/whitted.h with brute_force.h (every ray against every ellipsoid), which the
// tests hold the fast path to, byte for byte (src/render_reference.cpp; raytracer.exe
// takes it with --reference).
template <typename Real>
void render_reference_to(const Scene& scene, RowSink& sink, unsigned threads = 0);
template <typename Real>
Image render_reference(const Scene& scene, unsigned threads = 0) {
    ImageSink sink(scene.columns, scene.rows);
    render_reference_to<Real>(scene, sink, threads);
    return std::move(sink.image);
}

}  // namespace rt
