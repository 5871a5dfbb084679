// Per light, each ellipsoid's bounding sphere as the light sees it: the unit direction
// to its centre, the cosine and sine of its angular radius and its nearest distance.
// Two tests of shadow rays against them, both conservative: the lanes of a packet whose
// segment to the light may meet a sphere (one test per lane, vector instructions), and,
// before that, the spheres that the segment from ANY point of a ball around a packet's
// points may meet (one test per sphere, vector instructions over the spheres).
//
// WHY: the ball test rules out with one scalar set-up and a vector loop over the
// spheres every sphere near no lane's segment (half the packet-light pairs of the
// heavy scene), and the lane test is then only run for the spheres it leaves (under two
// per pair on the heavy scene). Both look at the segment itself, so they also rule out
// spheres beyond the point.
//
// Exactness: a segment from P to the light L that meets a sphere (centre S, radius R,
// inflated over the ellipsoid: sphere_bounds.h) has a point X in it, so the direction
// P - L lies within the sphere's angular radius b of S - L (sin b = R / |S - L|), and
// |X - L| <= |P - L| gives |P - L| >= |S - L| - R. A ball (c, r) of points seen from L
// lies within angle a (sin a = r / |c - L|) of c - L, at distances up to |c - L| + r;
// its segments can meet the sphere only if the angle between c - L and S - L is at most
// a + b, i.e. its cosine is at least cos(a + b) = cos a cos b - sin a sin b (a + b <=
// pi). A sphere ruled out this way cannot be met by intersect() on the segment, which is
// what the unculled renderer would test. Rounding of a few ulps is covered by kMargin on
// the cosines and distances, far above it; a sphere around the light is seen
// everywhere, and NaN compares as "may meet".
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/compiler.h"
#include "raytracer/flat_sweep/bounding_sphere.h"
#include "raytracer/flat_sweep/ellipsoid_set.h"
#include "raytracer/vec3.h"

namespace rt {

template <typename C>
class LightCones {
public:
    // A ball around a packet's points (usable = false: unknown, nothing is ruled out).
    struct Ball {
        C x = 0, y = 0, z = 0, radius = 0;
        bool usable = false;
    };

    LightCones() = default;

    LightCones(const std::vector<BoundingSphere<C>>& spheres, const std::vector<Vec3<C>>& lights)
        : n_(spheres.size()), stride_((spheres.size() + 7) / 8 * 8) {
        if (n_ > WideSet::kCapacity) return;
        const std::size_t size = stride_ * lights.size();
        // Padding spheres are never met: no direction has cosine 2 with a unit vector.
        ux_.assign(size, 0), uy_.assign(size, 0), uz_.assign(size, 0);
        cos_b_.assign(size, 2), sin_b_.assign(size, 0), near_.assign(size, 0);
        std::vector<WideSet> everywhere(lights.size());
        for (std::size_t l = 0; l < lights.size(); ++l)
            for (std::size_t j = 0; j < n_; ++j) {
                const BoundingSphere<C>& s = spheres[j];
                const SeenSphere<C> v = seen_from(lights[l].x, lights[l].y, lights[l].z, s, kMargin);
                if (v.everywhere) {  // around the light (or NaN)
                    everywhere[l].insert(j);
                    continue;
                }
                const std::size_t at = l * stride_ + j;
                ux_[at] = v.ux, uy_[at] = v.uy, uz_[at] = v.uz;
                sin_b_[at] = v.sin_b, cos_b_[at] = v.cos_b;
                near_[at] = v.distance * (C(1) - C(kMargin)) - s.radius * (C(1) + C(kMargin));
            }
        words_ = set_words(n_);
        everywhere_.resize(lights.size() * words_);
        for (std::size_t l = 0; l < lights.size(); ++l)
            everywhere[l].to_words(&everywhere_[l * words_], words_);
    }

    bool usable() const { return !everywhere_.empty(); }

    // A ball around the N points (px, py, pz)[k]: the centre of their box and half its
    // diagonal, widened by kMargin; not usable where a coordinate is not finite.
    template <int N>
    static Ball ball(const C* px, const C* py, const C* pz) {
        C lo_x = px[0], hi_x = px[0], lo_y = py[0], hi_y = py[0], lo_z = pz[0], hi_z = pz[0];
        C finite = 0;  // 0 while every coordinate is finite (x - x is 0, else NaN)
        for (int k = 0; k < N; ++k) {
            lo_x = px[k] < lo_x ? px[k] : lo_x, hi_x = px[k] > hi_x ? px[k] : hi_x;
            lo_y = py[k] < lo_y ? py[k] : lo_y, hi_y = py[k] > hi_y ? py[k] : hi_y;
            lo_z = pz[k] < lo_z ? pz[k] : lo_z, hi_z = pz[k] > hi_z ? pz[k] : hi_z;
            finite += (px[k] - px[k]) + (py[k] - py[k]) + (pz[k] - pz[k]);
        }
        using std::sqrt;
        Ball b;
        b.x = (lo_x + hi_x) / 2, b.y = (lo_y + hi_y) / 2, b.z = (lo_z + hi_z) / 2;
        const C ex = hi_x - lo_x, ey = hi_y - lo_y, ez = hi_z - lo_z;
        b.radius = sqrt(ex * ex + ey * ey + ez * ez) / 2 * (C(1) + C(kMargin));
        b.usable =
            finite == 0 && b.radius - b.radius == 0 && b.x - b.x == 0 && b.y - b.y == 0 && b.z - b.z == 0;
        return b;
    }

    // Of light l: the spheres among `among` that a segment from some point of the ball
    // to the light may meet. Set: at least as wide as set_words() of the spheres.
    template <typename Set>
    Set packet(std::size_t l, const Vec3<C>& light, const Ball& b, Set among) const {
        using std::sqrt;
        among &= Set::first(n_);  // only the spheres there are
        if (among.empty() || !b.usable) return among;
        const C wx = b.x - light.x, wy = b.y - light.y, wz = b.z - light.z;
        const C dist2 = wx * wx + wy * wy + wz * wz;
        const C dist = sqrt(dist2);
        if (!(dist > b.radius * (C(1) + C(kMargin)))) return among;  // the light is in the ball
        // dist cos(a) and dist sin(a): no division, and two square roots side by side.
        const C dist_cos_a = sqrt(dist2 - b.radius * b.radius), dist_sin_a = b.radius;
        const C margin = dist * C(kMargin);
        const C reach = dist + b.radius;
        const std::size_t base = l * stride_;
        Set set = Set::from_words(&everywhere_[l * words_], words_);
        for (std::size_t start = 0; start < stride_; start += 8) {
            const C *ux = &ux_[base + start], *uy = &uy_[base + start], *uz = &uz_[base + start];
            const C *cos_b = &cos_b_[base + start], *sin_b = &sin_b_[base + start],
                    *near = &near_[base + start];
            std::uint64_t eight = 0;  // spheres start to start + 7
            RT_VECTOR_LOOP
            for (int j = 0; j < 8; ++j) {
                const C along = wx * ux[j] + wy * uy[j] + wz * uz[j];
                const C least = dist_cos_a * cos_b[j] - dist_sin_a * sin_b[j] - margin;
                // Masks rather than ||, which keeps GCC's loop scalar.
                const C out = (along < least ? C(1) : C(0)) + (reach < near[j] ? C(1) : C(0));
                eight |= out != 0 ? 0 : kBit[j];
            }
            set.insert_bits(start, eight);
        }
        set &= among;
        return set;
    }

    // Of light l and sphere j: the lanes k (bit kLane[k]) whose segment from the point
    // at (fx, fy, fz)[k] = P - L from the light, of length d[k], may meet the sphere.
    template <int N>
    std::uint64_t lanes(std::size_t l, std::size_t j, const C* fx, const C* fy, const C* fz, const C* d,
                        const std::uint64_t (&lane_bit)[N]) const {
        if ((everywhere_[l * words_ + j / 64] >> (j % 64)) & 1U) return ~std::uint64_t(0);
        const std::size_t at = l * stride_ + j;
        const C ux = ux_[at], uy = uy_[at], uz = uz_[at];
        const C least = cos_b_[at] - C(kMargin), near = near_[at];
        std::uint64_t set = 0;
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const C out = (fx[k] * ux + fy[k] * uy + fz[k] * uz < d[k] * least ? C(1) : C(0)) +
                          (d[k] < near ? C(1) : C(0));
            set |= out != 0 ? 0 : lane_bit[k];
        }
        return set;
    }

private:
    static constexpr double kMargin = 1e-6;
    static constexpr std::uint64_t kBit[8] = {1, 2, 4, 8, 16, 32, 64, 128};

    std::size_t n_ = 0, stride_ = 0;                      // spheres, and per light a multiple of 8 of them
    std::vector<C> ux_, uy_, uz_, cos_b_, sin_b_, near_;  // [light * stride_ + sphere]
    std::size_t words_ = 0;                               // of a set: set_words(n_)
    std::vector<std::uint64_t> everywhere_;               // per light, words_ words: spheres around it
};

}  // namespace rt
