// render_to(): the path a scene takes (docs/speed.md), decided here: the flat sweep
// (flat_sweep/render_flat_sweep.cpp) within its range, unless it declines; the tree
// (render_tree.cpp) for every other scene.
#include "raytracer/render.h"

#include "raytracer/flat_sweep/render_flat_sweep.h"
#include "raytracer/render_tree.h"

namespace rt {

template <typename Real>
void render_to(const Scene& scene, RowSink& sink, unsigned threads) {
    // Past the range: more than 200 ellipsoids, too many pairs of ellipsoids and lights,
    // lengths its arithmetic cannot square (takes_the_tree()). Declined: float, or where
    // its tables say its packets would not pay (PacketTracer::can_render(): fewer pixels
    // than pairs of ellipsoids, thin ellipsoids it cannot cull).
    if (takes_the_tree(scene) || !render_flat_sweep_to<Real>(scene, sink, threads))
        render_tree_to<Real>(scene, sink, threads);
}

// raytracer.exe renders in double. The tests and the precision report render in float
// and long double too: this file is compiled a second time with RAYTRACER_EXTRA_PRECISIONS
// into raytracer_precisions (CMakeLists.txt) for those, so that the shipped program
// compiles one precision only (a third of the build).
#ifdef RAYTRACER_EXTRA_PRECISIONS
template void render_to<float>(const Scene&, RowSink&, unsigned);
template void render_to<long double>(const Scene&, RowSink&, unsigned);
#else
template void render_to<double>(const Scene&, RowSink&, unsigned);
#endif

}  // namespace rt
