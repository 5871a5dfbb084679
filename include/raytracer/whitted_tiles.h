// The reference path (whitted.h) for a tile of pixels at once: each pixel gets the bytes
// Whitted::pixel() gives it, from the same pieces of shade() in the same order, but the
// shadow rays of the tile's hits to one light go to the geometry as one bundle
// (Bvh::occluded() for lanes), which descends the tree once for all of them. The
// tile's reflected rays are traced as a tile in turn, down to the last bounce.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "raytracer/bit_scan.h"
#include "raytracer/spec_rules.h"
#include "raytracer/whitted.h"

namespace rt {

template <int N, typename Real, typename Geometry>
class WhittedTiles {
public:
    using Tracer = Whitted<Real, Geometry>;
    using V = Vec3<Real>;
    static_assert(N >= 1 && N <= 32, "a tile's lanes are the bits of an unsigned");

    explicit WhittedTiles(const Tracer& tracer) : tracer_(tracer) {}

    // The bytes of up to N pixels whose eye rays go from the camera through (x[k], y[k]),
    // for each lane k in lanes, to out[k].
    void pixels(const Real (&x)[N], const Real (&y)[N], unsigned lanes, std::uint8_t* const (&out)[N],
                typename Tracer::Scratch& scratch) const {
        V origin[N], direction[N], colour[N];
        for (int k = 0; k < N; ++k) origin[k] = {}, direction[k] = {x[k], y[k], tracer_.near_z()};
        trace(origin, direction, kEyeRayMinT, kMaxReflections, tracer_.background(), lanes, colour, scratch);
        for (unsigned m = lanes; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            out[k][0] = to_byte(colour[k].x), out[k][1] = to_byte(colour[k].y),
            out[k][2] = to_byte(colour[k].z);
        }
    }

private:
    // Whitted::trace() for each lane in lanes.
    void trace(const V (&origin)[N], const V (&direction)[N], double min_t, int reflections_left,
               const V& miss, unsigned lanes, V (&colour)[N], typename Tracer::Scratch& scratch) const {
        typename Tracer::Surface surface[N];
        unsigned hits = 0, lit = 0, reflecting = 0;
        NearestHit<Real> found[N];
        tracer_.geometry().closest(origin, direction, lanes, min_t, found);
        for (unsigned m = lanes; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            const NearestHit<Real>& hit = found[k];
            if (!hit.found()) {
                colour[k] = miss;
                continue;
            }
            surface[k] = tracer_.surface(hit, origin[k], direction[k], reflections_left);
            colour[k] = surface[k].material->ambient;
            hits |= 1U << k;
            lit |= surface[k].material->no_lighting ? 0U : 1U << k;
            reflecting |= surface[k].reflects ? 1U << k : 0U;
        }
        if (hits == 0) return;
        for (std::size_t li = 0; li < tracer_.light_count() && lit != 0; ++li) {
            typename Tracer::LightRay ray[N];
            V point[N];
            unsigned facing = 0;  // with a light ray to try
            for (unsigned m = lit; m != 0; m &= m - 1) {
                const int k = lowest_bit(m);
                ray[k] = tracer_.light_ray(surface[k], li);
                point[k] = surface[k].point;
                facing |= ray[k].faces ? 1U << k : 0U;
            }
            unsigned blocked = 0;
            for (unsigned left = facing; left != 0;) {
                const unsigned bundle = close_lanes(surface, left);
                left &= ~bundle;
                blocked |= tracer_.geometry().occluded(point, tracer_.light_position(li), bundle,
                                                       scratch.blockers[li]);
            }
            for (unsigned m = facing & ~blocked; m != 0; m &= m - 1) {
                const int k = lowest_bit(m);
                tracer_.add_light(colour[k], surface[k], li, ray[k]);
            }
        }
        if (reflecting == 0) return;
        V point[N], mirrored[N], seen[N];
        for (unsigned m = reflecting; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            point[k] = surface[k].point, mirrored[k] = Tracer::mirrored(surface[k], direction[k]);
        }
        trace(point, mirrored, kReflectedRayMinT, reflections_left - 1, V{}, reflecting, seen, scratch);
        for (unsigned m = reflecting; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            colour[k] += seen[k] * surface[k].ellipsoid->kr;
        }
    }

    // A bundle for the first of lanes: the lanes on its ellipsoid, when there are at
    // least kBundleLanes of them and their points lie within its smallest diameter of
    // each other (a tile seen on a sphere, or on the same side of a thin one), else the
    // first lane alone (say, reflected rays landing far apart on a floor, whose bundle
    // would sweep the scene). Measured (callgrind, sphereflakes 4 and 5): bundles of 2
    // or 3 rays cost more than the rays alone.
    static constexpr int kBundleLanes = 4;
    static unsigned close_lanes(const typename Tracer::Surface (&surface)[N], unsigned lanes) {
        const int first = lowest_bit(lanes);
        const Ellipsoid<Real>& e = *surface[first].ellipsoid;
        unsigned bundle = 0;
        V lo = surface[first].point, hi = lo;
        for (unsigned m = lanes; m != 0; m &= m - 1) {
            const int k = lowest_bit(m);
            if (surface[k].ellipsoid != &e) continue;
            bundle |= 1U << k;
            const V& p = surface[k].point;
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
        using std::abs;
        const Real diameter = 2 * std::min({abs(e.scale.x), abs(e.scale.y), abs(e.scale.z)});
        const bool close = hi.x - lo.x <= diameter && hi.y - lo.y <= diameter && hi.z - lo.z <= diameter;
        return close && bit_count(bundle) >= kBundleLanes ? bundle : 1U << first;
    }

    const Tracer& tracer_;
};

}  // namespace rt
