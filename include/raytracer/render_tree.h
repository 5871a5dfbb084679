// The tree's path: the reference's shading (whitted.h) a tile at a time, with the
// acceleration layer (bvh.h) answering the geometry queries. render_to() takes it for
// scenes beyond the flat sweep's range (takes_the_tree()) and for those the flat sweep
// declines (render_flat_sweep_to()).
#pragma once

#include "raytracer/row_sink.h"
#include "raytracer/scene.h"

namespace rt {

// Instantiated for double in raytracer.exe, for float and long double in
// raytracer_precisions (render.cpp); threads = 0: all cores.
template <typename Real>
void render_tree_to(const Scene& scene, RowSink& sink, unsigned threads = 0);

}  // namespace rt
