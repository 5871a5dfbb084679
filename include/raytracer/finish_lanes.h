// A Finish (shading.h) over lanes: set lane by lane for a tile of hits on several
// ellipsoids (whitted_tiles.h), or the same in every lane for a packet of hits on one
// (the flat sweep's hit_packet.h).
#pragma once

#include <cstdint>

#include "raytracer/lanes.h"
#include "raytracer/reference/shading.h"
#include "raytracer/vec3.h"

namespace rt {

// Lane k of a tile's Finish; its shared_exponent unknown (-1) until share_exponent()
// finds it, once every lane is set.
template <int N, typename Real>
void set_lane(Finish<Lanes<Real, N>>& lanes, int k, const Finish<Real>& f) {
    set_lane(lanes.colour, k, f.colour);
    lanes.kd[k] = f.kd, lanes.ks[k] = f.ks, lanes.shininess[k] = f.shininess, lanes.exponent[k] = f.exponent;
    lanes.shared_exponent = -1;
    lanes.specular = (lanes.specular & ~kLaneBits<N>.bit[k]) | (f.specular ? kLaneBits<N>.bit[k] : 0);
}

template <int N, typename Real>
void share_exponent(Finish<Lanes<Real, N>>& f) {
    f.shared_exponent = f.exponent[0];
    for (int k = 1; k < N; ++k) f.shared_exponent = f.exponent[k] == f.exponent[0] ? f.shared_exponent : -1;
}

// A Finish the same in every lane (a packet of hits on one ellipsoid).
template <int N, typename Real>
Finish<Lanes<Real, N>> every_lane(const Finish<Real>& f) {
    return {Vec3<Lanes<Real, N>>::from(f.colour),
            f.kd,
            f.ks,
            f.shininess,
            f.exponent,
            f.exponent,
            f.specular ? LaneBits(~LaneBits(0) >> (64 - N)) : LaneBits(0)};
}

}  // namespace rt
