// The flat sweep's tracer of SPEC sections 3-5: its shortcuts' tables, built once per
// scene, and the packets that shade hits with them (packet_shading.h); a template on the
// scalar type, for double (raytracer.exe) and long double (the tests).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raytracer/flat_sweep/bounding_sphere.h"
#include "raytracer/flat_sweep/ellipsoid_set.h"
#include "raytracer/flat_sweep/enclosures.h"
#include "raytracer/flat_sweep/hit_packet.h"
#include "raytracer/flat_sweep/light_cones.h"
#include "raytracer/flat_sweep/render_flat_sweep.h"
#include "raytracer/flat_sweep/screen_bounds.h"
#include "raytracer/flat_sweep/sphere_bounds.h"
#include "raytracer/image.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/shading.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/scene.h"
#include "raytracer/vec3.h"

namespace rt {

// Per-thread working memory of a PacketTracer, so that no ray allocates: the candidate lists
// of the bounding-sphere culling and, per light, the ellipsoid that last blocked it; on
// cache lines of its own (own_cache_lines.h).
template <typename Real>
struct TraceScratch {
    OwnLinesVector<std::uint32_t> candidates;
    OwnLinesVector<typename SphereBounds<Real>::C> cone_misses;  // per ellipsoid: culled when not 0
    OwnLinesVector<std::uint32_t> blocker_hints;  // per light, the last blocker; kNoEllipsoid before any
    OwnLinesVector<std::uint32_t> lanes;          // per ellipsoid: the rays that may hit it
};

template <typename Real>
class PacketTracer {
public:
    using V = Vec3<Real>;
    using C = typename SphereBounds<Real>::C;  // the precision of the culling arithmetic
    static_assert(kFlatSweepPrecision<Real>, "the flat sweep renders in double or wider");

    // The reference that the tests hold this tracer's images to, byte for byte, is
    // whitted.h with brute_force.h (render_reference()).
    explicit PacketTracer(const Scene& scene)
        : ellipsoids_(make_ellipsoids<Real>(scene)),
          lights_(point_lights<Real>(scene)),
          background_(V::from(scene.background)) {
        const V ambient_light = V::from(scene.ambient);
        for (const Ellipsoid<Real>& e : ellipsoids_) surfaces_.push_back(surface_constants(ambient_light, e));
        bounds_ = SphereBounds<Real>(ellipsoids_);
        for (const Ellipsoid<Real>& e : ellipsoids_) eye_origin_.push_back(mapped_origin(e, V{}));
        enclosures_ = Enclosures<Real>(ellipsoids_, positions_of(lights_));
        // Shadow rays are tested a packet at a time (lit_lanes()) and no other way, so
        // the flat sweep renders a scene only where that pays (can_render(); the tree
        // takes the others): where the image has at least as many pixels as there are
        // pairs of ellipsoids (its tables are made per scene, the image's shadow rays
        // grow with its pixels: 200 random ellipsoids with 10 lights, whole process,
        // medians of 15, took 7.35 ms in the tree against 7.77 flat at 150x150, 5.5
        // against 6.7 at 100x100, and the same at 200x200). Where no eye ray can hit
        // anything there is no shadow ray at all, and the light cones are not built
        // (0.04 ms of testBehind's 1.8 ms run). The light cones that cull the candidates
        // are exact only where rounding stays far below the spheres' inflation
        // (everything_guarded()); elsewhere each packet tries every ellipsoid on every
        // lane, with the prefilter and intersect(), exact at any distance but slow past
        // a few ellipsoids, where the tree, whose boxes grow for thin ellipsoids, is far
        // faster (kUnculledEllipsoids).
        screen_rects_ = screen_bounds(scene, bounds_.spheres(), culls_eye_rays());
        any_seen_ = std::any_of(screen_rects_.begin(), screen_rects_.end(), [](const PixelRect& r) {
            return r.first_column <= r.last_column && r.first_row <= r.last_row;
        });
        const double pixels = double(scene.columns) * double(scene.rows);
        const double n = double(ellipsoids_.size());
        const bool guarded = everything_guarded();
        // (WideSet::kCapacity: always within takes_the_tree()'s range; the tests call
        // this tracer for larger scenes too.)
        can_render_ = !any_seen_ || (pixels >= n * n && ellipsoids_.size() <= WideSet::kCapacity &&
                                     (guarded || ellipsoids_.size() <= kUnculledEllipsoids));
        culling_tables_ = any_seen_ && can_render_ && guarded;
        if (culling_tables_) {
            std::vector<Vec3<C>> positions;
            for (const PointLight<Real>& l : lights_) positions.push_back(Vec3<C>::from(l.position));
            light_cones_ = LightCones<C>(bounds_.spheres(), positions);
        }
    }

    // Whether the flat sweep renders the scene (see the constructor); else the tree does.
    bool can_render() const { return can_render_; }
    // The most ellipsoids it renders without its culling tables. Rendering alone, one
    // thread, medians of 11 (2026-12-05): 4 / 8 / 15 / 120 random discs 0.3 x 1e-9 x 0.3
    // took 1.8 / 3.4 / 6.4 / 54.6 ms in the flat sweep against 0.06 / 0.06 / 0.08 / 0.45
    // ms in the tree; the heavy scene with one ellipsoid 1e-7 thick 270 against 160 ms;
    // scenes/hard's disc_1e-15, thin_1e-9 and floor_1e8 (2, 3 and 4 ellipsoids, filling
    // the screen) 0.08 / 0.32 / 0.98 ms against 0.96 / 0.49 / 1.37 ms.
    static constexpr std::size_t kUnculledEllipsoids = 4;

    // Working memory for one thread's rays.
    TraceScratch<Real> make_scratch() const {
        TraceScratch<Real> s;
        s.candidates.resize(ellipsoids_.size());
        s.cone_misses.resize(ellipsoids_.size());
        s.blocker_hints.assign(lights_.size(), kNoEllipsoid);
        s.lanes.resize(ellipsoids_.size());
        return s;
    }

    // Per ellipsoid, the pixels outside which no eye ray meets it (screen_bounds.h).
    const std::vector<PixelRect>& screen_rects() const { return screen_rects_; }
    // Whether some pixel may see an ellipsoid: else every pixel is the background.
    bool sees_any() const { return any_seen_; }

    // Up to kPacket eye-ray hits on ellipsoid i at once: pixel k < count looks along
    // (dx[k], dy[k], dz[k]) and meets the ellipsoid first at t[k] (inside[k]: the far
    // root); its three bytes go to out[k], those the reference gives the pixel
    // (Whitted::pixel(), whitted.h).
    //
    // Why in packets: hit_packet.h. Every lane does the operations of the reference's
    // shading (shading.h) in its order, and a term that it skips is not added (a select,
    // not an addition of zero), so the bytes are the same.
    static constexpr int kPacket = rt::kPacket;
    void eye_hit_pixels(std::uint32_t i, int count, const Real* dx, const Real* dy, const Real* dz,
                        const Real* t, const bool* inside, TraceScratch<Real>& scratch,
                        std::uint8_t* const* out) const {
        V colours[kPacket];
        eye_hit_colours(i, count, dx, dy, dz, t, inside, scratch, colours);
        for (int k = 0; k < count; ++k) pixel_bytes(colours[k], out[k]);
    }
    // The bytes of every pixel that sees ellipsoid i where its colour is its ambient term
    // alone (ambient_only()), else nullptr.
    const std::uint8_t* ambient_only_bytes(std::uint32_t i) const {
        return surfaces_[i].ambient_only ? surfaces_[i].ambient_bytes : nullptr;
    }
    // The same as colours (before conversion to bytes).
    void eye_hit_colours(std::uint32_t i, int count, const Real* dx, const Real* dy, const Real* dz,
                         const Real* t, const bool* inside, TraceScratch<Real>& scratch, V* colours) const {
        const Real camera[kPacket] = {};
        packet_width(count, [&](auto width) {
            hit_colours<decltype(width)::value>(i, count, camera, camera, camera, dx, dy, dz, t, inside,
                                                kMaxReflections, scratch, colours);
        });
    }

    // Per ellipsoid, the ellipsoid and the camera's terms in its unit space
    // (mapped_origin()), for eye rays intersected by the caller.
    const Ellipsoid<Real>& ellipsoid(std::size_t i) const { return ellipsoids_[i]; }
    const MappedOrigin<Real>& eye_origin(std::size_t i) const { return eye_origin_[i]; }

    // Per ellipsoid, the columns of a row that may see it (screen_bounds.h).
    RowSpans<C> row_spans(const Scene& scene) const {
        return RowSpans<C>(scene, ellipsoids_, culls_eye_rays());
    }

    const V& background() const { return background_; }
    // The nearest hits of N rays at once, each as the reference's closest() finds it
    // (packet_shading.h).
    template <int N = kPacket>
    void nearest_hits(const Real* ox, const Real* oy, const Real* oz, const Real* dx, const Real* dy,
                      const Real* dz, Real min_t, TraceScratch<Real>& scratch, std::uint32_t* index, Real* t,
                      bool* inside) const;

private:
    // Whether rounding is far below the spheres' inflation (sphere_bounds.h) for the box
    // of everything a ray can start from or go to: the ellipsoids' spheres, the lights
    // and the camera. Packet shadows are exact only then.
    bool everything_guarded() const {
        Vec3<C> lo{}, hi{};  // from the camera, at the origin
        auto grow = [&](C x, C y, C z, C r) {
            lo = {std::min(lo.x, x - r), std::min(lo.y, y - r), std::min(lo.z, z - r)};
            hi = {std::max(hi.x, x + r), std::max(hi.y, y + r), std::max(hi.z, z + r)};
        };
        for (std::size_t i = 0; i < bounds_.size(); ++i) {
            const BoundingSphere<C> s = bounds_.sphere(i);
            grow(s.x, s.y, s.z, s.radius);
        }
        for (const PointLight<Real>& l : lights_) grow(C(l.position.x), C(l.position.y), C(l.position.z), 0);
        return bounds_.guards(lo, hi);
    }

    // The packets, in packet_shading.h: the colours of up to N hits on one ellipsoid,
    // where their points lie, their shadow rays to one light, their mirrored rays.
    template <int N>
    void hit_colours(std::uint32_t i, int count, const Real* ox, const Real* oy, const Real* oz,
                     const Real* dx, const Real* dy, const Real* dz, const Real* t, const bool* inside,
                     int reflections_left, TraceScratch<Real>& scratch, V* colours) const;
    struct PacketPlace;
    // Lights are shaded in batches of this many (hit_colours()).
    static constexpr std::size_t kLightBatch = 4;
    template <int N>
    PacketPlace packet_place(const HitPacket<Real, N>& p, std::uint32_t i) const;
    template <int N, typename Set>
    void shadow_batch(const HitPacket<Real, N>& p, const PacketPlace& place, std::uint32_t i,
                      std::size_t first, std::size_t size, LightLanes<Real, N>* batch, bool* lit_any,
                      TraceScratch<Real>& scratch) const;
    template <int N, typename Set>
    std::uint64_t lit_lanes(const HitPacket<Real, N>& p, LightLanes<Real, N>& l, std::uint32_t self,
                            std::size_t li, Set may_block, std::uint64_t self_within,
                            TraceScratch<Real>& scratch) const;
    template <int N>
    void reflections(HitPacket<Real, N>& p, Real kr, int reflections_left, TraceScratch<Real>& scratch) const;

    // Per ellipsoid, whether its bounding sphere may cull rays from the camera.
    std::vector<bool> culls_eye_rays() const {
        std::vector<bool> culls;
        for (std::size_t i = 0; i < bounds_.size(); ++i)
            culls.push_back(bounds_.guards({0, 0, 0}, {0, 0, 0}, i));
        return culls;
    }

    std::vector<Ellipsoid<Real>> ellipsoids_;
    std::vector<PointLight<Real>> lights_;
    std::vector<SurfaceConstants<Real>> surfaces_;  // per ellipsoid
    SphereBounds<Real> bounds_;
    std::vector<MappedOrigin<Real>> eye_origin_;  // per ellipsoid, of the camera
    std::vector<PixelRect> screen_rects_;         // per ellipsoid
    bool any_seen_ = false;                       // some rect holds a pixel
    bool can_render_ = false;
    bool culling_tables_ = false;  // light_cones_ built and exact
    Enclosures<Real> enclosures_;
    LightCones<C> light_cones_;  // where culling_tables_
    V background_;
};

}  // namespace rt

#include "raytracer/flat_sweep/packet_shading.h"  // the packets: PacketTracer's members defined there
