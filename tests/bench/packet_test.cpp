// PacketTracer::eye_hit_pixels() shades up to kPacket eye-ray hits at once with vector
// instructions (hit_packet.h); each pixel's colour must equal, bit for bit, the
// reference's for that pixel alone (Whitted::eye_ray_colour(), whitted.h), and its bytes
// to_byte() of it, in double and long double (the flat sweep's precisions): for packets
// of neighbouring pixels, of pixels scattered over a row, and partial packets. Scenes the
// flat sweep hands to the tree (PacketTracer::can_render()) are left out.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "check.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/image.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/whitted.h"
#include "scale_scenes.h"
#include "stress_scenes.h"

namespace {

// Equal values with equal signs (0 and -0 differ), or both NaN: the same bits but for
// a NaN's payload and long double's padding.
template <typename Real>
bool same(Real a, Real b) {
    return (a == b && std::signbit(a) == std::signbit(b)) || (a != a && b != b);
}

template <typename Real>
struct EyeHit {
    std::uint32_t ellipsoid;
    Real x, y, z, t;
    bool inside;
    int column;
};

// Renders every row of the scene twice, pixel by pixel and in packets of the given
// size (gathering the row's hits on each ellipsoid in column order, every stride-th
// first), and counts the bytes and the colours that differ.
template <typename Real>
long long differing_bytes(const rt::Scene& scene, int packet, int stride) {
    using V = rt::Vec3<Real>;
    const rt::PacketTracer<Real> tracer(scene);
    rt::TraceScratch<Real> scratch = tracer.make_scratch();
    const rt::Whitted<Real, rt::BruteForce<Real>> reference(
        scene, rt::BruteForce<Real>(rt::make_ellipsoids<Real>(scene)));
    auto reference_scratch = reference.make_scratch();
    const rt::BruteForce<Real> plain(rt::make_ellipsoids<Real>(scene));
    long long differing = 0;
    for (int r = 0; r < scene.rows; ++r) {
        std::vector<EyeHit<Real>> hits;
        const Real y = reference.row_y(r);
        for (int c = 0; c < scene.columns; ++c) {
            const Real x = reference.column_x(c);
            const V d{x, y, -Real(scene.near_plane)};
            const auto hit = plain.closest(V{}, d, rt::kEyeRayMinT);
            if (!hit.found()) continue;
            hits.push_back({hit.ellipsoid, d.x, d.y, d.z, hit.t, hit.inside, c});
        }
        std::vector<std::uint8_t> one(std::size_t(scene.columns) * 3), many(one.size());
        std::vector<V> one_colour(std::size_t(scene.columns)), many_colour(one_colour.size());
        for (const EyeHit<Real>& h : hits) {
            const V colour = reference.eye_ray_colour({h.x, h.y, h.z}, reference_scratch);
            one_colour[std::size_t(h.column)] = colour;
            std::uint8_t* const pixel = one.data() + std::size_t(h.column) * 3;
            pixel[0] = rt::to_byte(colour.x), pixel[1] = rt::to_byte(colour.y),
            pixel[2] = rt::to_byte(colour.z);
        }
        // Packets of hits on one ellipsoid, in the order (k mod stride, k).
        for (std::uint32_t e = 0; e < scene.spheres.size(); ++e) {
            std::vector<const EyeHit<Real>*> on;
            for (int phase = 0; phase < stride; ++phase)
                for (std::size_t k = std::size_t(phase); k < hits.size(); k += std::size_t(stride))
                    if (hits[k].ellipsoid == e) on.push_back(&hits[k]);
            for (std::size_t first = 0; first < on.size(); first += std::size_t(packet)) {
                Real dx[rt::kPacket], dy[rt::kPacket], dz[rt::kPacket], t[rt::kPacket];
                bool inside[rt::kPacket];
                std::uint8_t* out[rt::kPacket];
                V colours[rt::kPacket];
                int count = 0;
                for (std::size_t k = first; k < on.size() && count < packet; ++k, ++count) {
                    dx[count] = on[k]->x, dy[count] = on[k]->y, dz[count] = on[k]->z, t[count] = on[k]->t;
                    inside[count] = on[k]->inside;
                    out[count] = many.data() + std::size_t(on[k]->column) * 3;
                }
                tracer.eye_hit_pixels(e, count, dx, dy, dz, t, inside, scratch, out);
                tracer.eye_hit_colours(e, count, dx, dy, dz, t, inside, scratch, colours);
                for (int k = 0; k < count; ++k)
                    many_colour[std::size_t(on[std::size_t(k) + first]->column)] = colours[k];
            }
        }
        for (std::size_t k = 0; k < one.size(); ++k) differing += one[k] != many[k];
        // The colours bit for bit (a reordered sum moves one ulp, rarely a byte).
        for (std::size_t k = 0; k < one_colour.size(); ++k)
            differing += !same(one_colour[k].x, many_colour[k].x) ||
                         !same(one_colour[k].y, many_colour[k].y) || !same(one_colour[k].z, many_colour[k].z);
    }
    return differing;
}

// Scenes left out because the flat sweep hands them to the tree.
int left_out = 0;

template <typename Real>
bool packets_match(const std::string& name, const rt::Scene& scene) {
    if (!rt::PacketTracer<Real>(scene).can_render()) {
        ++left_out;
        return true;
    }
    bool all = true;
    // Full packets of neighbours, full packets of scattered pixels, partial packets.
    const std::pair<int, int> shapes[] = {{rt::kPacket, 1}, {rt::kPacket, 3}, {3, 1}};
    for (const auto& [packet, stride] : shapes) {
        const long long d = differing_bytes<Real>(scene, packet, stride);
        if (d != 0)
            std::cerr << name << " (" << sizeof(Real) << "-byte reals, packets of " << packet << ", stride "
                      << stride << "): " << d << " bytes differ\n";
        all = all && d == 0;
    }
    return all;
}

}  // namespace

TEST(packets_of_scene_file_pixels_match_single_pixels) {
    left_out = 0;
    for (const auto& [name, scene] : stress::file_scenes(83, 67)) {
        CHECK(packets_match<double>(name, scene));
        CHECK(packets_match<long double>(name, scene));
    }
    CHECK_EQ(left_out, 0);
}

TEST(packets_of_random_scene_pixels_match_single_pixels) {
    left_out = 0;
    for (unsigned seed = 1; seed <= 40; ++seed) {
        const rt::Scene scene = stress::random_scene(seed);
        const std::string name = "random scene " + std::to_string(seed);
        CHECK(packets_match<double>(name, scene));
        CHECK(packets_match<long double>(name, scene));
    }
    CHECK(left_out <= 8);  // the scenes are built to stress the shortcuts, not to avoid them
}

// Past 64 ellipsoids, where the packets' shadow sets are wider than a word.
TEST(packets_of_a_crowd_match_single_pixels) {
    left_out = 0;
    rt::Scene crowd = scale::random_ellipsoids(130, 7);
    crowd.columns = crowd.rows = 130;  // as many pixels as pairs: the flat sweep's
    CHECK(packets_match<double>("random 130", crowd));
    CHECK(packets_match<long double>("random 130", crowd));
    CHECK_EQ(left_out, 0);
}
