// The reference path (whitted.h) for a tile of pixels at once: each pixel gets the bytes
// Whitted::pixel() gives it, from the same pieces of shade() in the same order, but the
// eye rays of two tiles go down the tree as one block (eye_block.h), and per light the
// shadow rays of a tile's hits on one ellipsoid, where at least four lie close together,
// as one bundle (close_lanes(), Bvh::occluded() for lanes); the rest go ray by ray. The
// tile's reflected rays are traced as a tile in turn, down to the last bounce.
//
// The parts of the image, largest first:
//   band   Rows rows, one job of render_bands() (kBandRows);
//   span   kSpanColumns columns of a band, drawn as BACK at once where no eye ray of it
//          can meet a box (Bvh::may_meet());
//   block  kBlockColumns columns of a span, whose eye rays descend the tree together
//          (EyeBlock);
//   tile   Rows x Columns pixels of a block, shaded together as N lanes;
//   chunk  kChunk lanes of a tile, one vector register (kRegisterLanes).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "raytracer/accel/blocker_hints.h"
#include "raytracer/accel/cleared_lanes.h"
#include "raytracer/accel/exact_culling.h"
#include "raytracer/accel/eye_block.h"
#include "raytracer/accel/light_shells.h"
#include "raytracer/accel/slab_rays.h"
#include "raytracer/bit_scan.h"
#include "raytracer/finish_lanes.h"
#include "raytracer/image.h"
#include "raytracer/lanes.h"
#include "raytracer/own_cache_lines.h"
#include "raytracer/reference/shading.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/scene_precision.h"

namespace rt {

template <typename Real, typename Geometry, int Rows, int Columns>
class WhittedTiles {
public:
    using Tracer = Whitted<Real, Geometry>;
    using V = Vec3<Real>;
    static constexpr int N = Rows * Columns;  // a tile's lanes: pixel (b, c) is lane b * Columns + c
    static_assert(N >= 1 && N <= 32, "a tile's lanes are the bits of an unsigned");
    static_assert(N % kRegisterLanes<Real, N> == 0, "whole registers");

    explicit WhittedTiles(const Tracer& tracer)
        : tracer_(tracer), hints_(tracer.ellipsoid_count(), tracer.light_count()) {
        shells_ = LightShells<Real>(tracer.geometry(), positions_of(tracer.lights()));
        std::uint8_t background[kBytesPerPixel];
        pixel_bytes(tracer.background(), background);
        for (int c = 0; c < kSpanColumns; ++c)
            std::memcpy(background_row_ + bytes_of_pixels(c), background, kBytesPerPixel);
    }

    // One bounce's lanes: the rays, what they hit, and their colours. The eye rays'
    // origins (bounce 0) are the camera's (0, 0, 0) from the scratch's making on:
    // nothing writes them. The shading runs a vector register of lanes at a time
    // (kChunk lanes: over all N at once its chains spill their registers, as the flat
    // sweep's packets measured, hit_packet.h). Lanes not in play hold what an earlier
    // tile left: their arithmetic runs and is never read.
    static constexpr int kChunk = kRegisterLanes<Real, N>, kChunks = N / kChunk;
    using Q = Lanes<Real, kChunk>;  // a number per lane of a chunk (lanes.h)
    struct Chunk {
        Vec3<Q> origin, direction, centre, scale, scale_squared, ambient_term;  // each hit's terms
        Q t, kr;
        Finish<Q> finish;
        SurfacePoint<Q> surface;
        Q abs_c;  // own_abs_c()
        Vec3<Q> colour;
    };
    struct Bounce {
        V origin[N], direction[N];  // as the geometry's bundle queries take them
        NearestHit<Real> hit[N];
        V point[N];        // the hit points, for the shadow bundles and the next bounce
        unsigned same[N];  // the hits on lane k's ellipsoid (lanes_on_one_ellipsoid())
        Chunk chunk[kChunks];
        Vec3<Real> colour(int k) const { return lane(chunk[k / kChunk].colour, k % kChunk); }
    };
    // A thread's working memory: the lanes of each bounce, made once (a tile's arrays
    // are a few KB: set up per tile, they cost more than a missed tile's tracing), on
    // cache lines of its own (own_cache_lines.h).
    struct Scratch {
        OwnLinesVector<Bounce> bounces;
    };
    Scratch make_scratch() const { return {OwnLinesVector<Bounce>(kMaxReflections + 1)}; }

    // The bytes of a band of `rows` <= Rows rows, the eye rays of row b through y[b] on
    // the near plane and its bytes from out[b], and `columns` columns, column c's through
    // column_x[c]. A span whose eye rays can meet no ellipsoid's box gets BACK's bytes at
    // once; in the others the eye rays go to the tree a block at a time, and are shaded a
    // tile at a time. Blocks of two tiles and spans of four blocks: blocks of 32 columns
    // were up to 5% slower on sphereflake 5 and random 100k (docs/speed.md, "Tried and
    // dropped").
    static constexpr int kBlockColumns = 2 * Columns, kSpanColumns = 4 * kBlockColumns;
    void band(const Real* column_x, int columns, const Real* y, std::uint8_t* const* out, int rows,
              Scratch& scratch) const {
        using C = AtLeastDouble<Real>;
        C y_lo = C(y[0]), y_hi = C(y[0]);
        for (int b = 1; b < rows; ++b) y_lo = std::min(y_lo, C(y[b])), y_hi = std::max(y_hi, C(y[b]));
        const C near_z = C(tracer_.near_z());
        for (int span = 0; span < columns; span += kSpanColumns) {
            const int span_end = std::min(span + kSpanColumns, columns);
            // column_x is monotonic (each operation of pixel_x() is): a span's
            // range is that of its ends.
            const C x_first = C(column_x[span]), x_last = C(column_x[span_end - 1]);
            const C x_lo = std::min(x_first, x_last), x_hi = std::max(x_first, x_last);
            if (tracer_.geometry().may_meet(V{}, {x_lo, y_lo, near_z}, {x_hi, y_hi, near_z})) {
                for (int block = span; block < span_end; block += kBlockColumns)
                    shade_block(column_x, block, std::min(block + kBlockColumns, span_end), y, out, rows,
                                scratch);
                continue;
            }
            fill_background(out, rows, span, span_end);
        }
    }

private:
    // BACK's bytes into columns [first, last) of the band's rows.
    void fill_background(std::uint8_t* const* out, int rows, int first, int last) const {
        for (int b = 0; b < rows; ++b)
            std::memcpy(out[b] + bytes_of_pixels(first), background_row_, bytes_of_pixels(last - first));
    }

    // The pixels of columns [first, last) of a band (band()): their eye rays' hits from
    // the tree, then tiles of those that hit something shaded; BACK where they miss.
    void shade_block(const Real* column_x, int first, int last, const Real* y, std::uint8_t* const* out,
                     int rows, Scratch& scratch) const {
        EyeBlock<Real, Rows, kBlockColumns> rays(column_x + first, last - first, y, rows, tracer_.near_z());
        tracer_.geometry().closest(rays);
        Bounce& eye = scratch.bounces[0];
        for (int c0 = first; c0 < last; c0 += Columns) {
            const int c_end = std::min(c0 + Columns, last);
            fill_background(out, rows, c0, c_end);  // where a ray misses; a hit's bytes overwrite it
            if (!rays.tried()) continue;
            std::uint8_t* tile_out[N];  // only the lanes in hits are read
            unsigned hits = 0;
            for (int b = 0; b < rows; ++b)
                for (int c = c0; c < c_end; ++c) {
                    const int k = b * Columns + (c - c0);
                    eye.hit[k] = rays.hit(b, c - first);
                    if (!eye.hit[k].found()) continue;
                    std::uint8_t* const bytes = out[b] + bytes_of_pixels(c);
                    // An ellipsoid no light nor mirror adds to: its bytes are known.
                    if (const SurfaceConstants<Real>& s = tracer_.surface(eye.hit[k].ellipsoid);
                        s.ambient_only) {
                        std::memcpy(bytes, s.ambient_bytes, kBytesPerPixel);
                        continue;
                    }
                    eye.direction[k] = {column_x[c], y[b], tracer_.near_z()};
                    tile_out[k] = bytes;
                    hits |= 1U << k;
                }
            if (hits == 0) continue;
            shade(0, hits, scratch);
            for (unsigned m = hits; m != 0; m &= m - 1)
                pixel_bytes(eye.colour(lowest_bit(m)), tile_out[lowest_bit(m)]);
        }
    }

    // Whitted::trace() for each lane in lanes of a bounce of mirrored rays (depth >= 1,
    // which see black where they miss): shade() of what they hit.
    void trace(int depth, unsigned lanes, Scratch& scratch) const {
        Bounce& b = scratch.bounces[static_cast<std::size_t>(depth)];
        tracer_.geometry().closest(b.origin, b.direction, lanes, kReflectedRayMinT, b.hit);
        shade(depth, lanes, scratch);
    }

    // Whitted::shade() for each lane in lanes of bounce `depth` (0: the eye rays) given
    // b.hit: its rays' colours, black where a mirrored ray misses (eye rays come here only
    // where they hit). Its arithmetic for all lanes (shading.h over Lanes, a chunk at a
    // time), its branches as lane sets.
    void shade(int depth, unsigned lanes, Scratch& scratch) const {
        Bounce& b = scratch.bounces[static_cast<std::size_t>(depth)];
        const HitLanes h = gather(b, lanes, kMaxReflections - depth);
        const Vec3<Q> miss = Vec3<Q>::from(V{});
        static_assert(LightShells<Real>::kMax + 1 <= ClearedLanes::kMax, "room for the shells and the own");
        unsigned in_shell[LightShells<Real>::kMax] = {};  // the lanes whose points each shell holds
        for (int i = 0; i < kChunks; ++i) {
            Chunk& c = b.chunk[i];
            const LaneBits hit = part(h.hits, i);
            c.colour = select(hit, c.ambient_term, miss);
            if (hit == 0) continue;
            c.surface =
                surface_point(c.origin, c.direction, c.t, part(h.inside, i), c.centre, c.scale_squared);
            c.abs_c = own_abs_c(c.surface.point, c.centre, c.scale);
            for (LaneBits m = hit; m != 0; m &= m - 1)
                b.point[i * kChunk + lowest_bit(m)] = lane(c.surface.point, lowest_bit(m));
            for (int s = 0; s < shells_.count(); ++s)
                in_shell[s] |= static_cast<unsigned>(shells_.holding(s, c.surface.point) << (i * kChunk));
        }
        if (h.hits == 0) return;
        for (std::size_t li = 0; li < tracer_.light_count() && h.lightable != 0; ++li)
            add_light_lanes(b, h, li, in_shell);
        if (h.reflecting == 0) return;
        Bounce& next = scratch.bounces[static_cast<std::size_t>(depth) + 1];
        for (int i = 0; i < kChunks; ++i) {
            const LaneBits mirrors = part(h.reflecting, i);
            if (mirrors == 0) continue;
            const Vec3<Q> onward = mirrored(b.chunk[i].surface.normal, b.chunk[i].direction);
            for (LaneBits m = mirrors; m != 0; m &= m - 1) {
                const int j = lowest_bit(m), k = i * kChunk + j;
                next.origin[k] = b.point[k], next.direction[k] = lane(onward, j);
            }
        }
        trace(depth + 1, h.reflecting, scratch);
        for (int i = 0; i < kChunks; ++i) {
            const LaneBits mirrors = part(h.reflecting, i);
            Chunk& c = b.chunk[i];
            if (mirrors != 0) c.colour = select(mirrors, c.colour + next.chunk[i].colour * c.kr, c.colour);
        }
    }

    // The lanes of a bounce that hit something, that some light may reach (Kd or Ks
    // not 0), that reflect (Kr > 0, a bounce left), and that see an inner surface.
    struct HitLanes {
        unsigned hits = 0, lightable = 0, reflecting = 0;
        LaneBits inside = 0;
    };
    // Each hit's terms into its lane.
    HitLanes gather(Bounce& b, unsigned lanes, int reflections_left) const {
        HitLanes h;
        for (unsigned m = lanes; m != 0; m &= m - 1) {
            const int k = lowest_bit(m), j = k % kChunk;
            const NearestHit<Real>& hit = b.hit[k];
            if (!hit.found()) continue;
            const Ellipsoid<Real>& e = tracer_.geometry().ellipsoid(hit.ellipsoid);
            const SurfaceConstants<Real>& surface = tracer_.surface(hit.ellipsoid);
            Chunk& c = b.chunk[k / kChunk];
            set_lane(c.origin, j, b.origin[k]), set_lane(c.direction, j, b.direction[k]);
            set_lane(c.centre, j, e.centre), set_lane(c.scale, j, e.scale),
                set_lane(c.scale_squared, j, e.scale_squared);
            set_lane(c.ambient_term, j, surface.ambient_term);
            c.t[j] = hit.t, c.kr[j] = e.kr;
            set_lane(c.finish, j, finish_of(e));
            h.inside |= hit.inside ? LaneBits(1) << k : 0;
            h.hits |= 1U << k;
            h.lightable |= surface.no_lighting ? 0U : 1U << k;
            h.reflecting |= reflects(e, reflections_left) ? 1U << k : 0U;
        }
        for (Chunk& c : b.chunk) share_exponent(c.finish);
        lanes_on_one_ellipsoid(b, h.hits);
        return h;
    }

    // b.same[k] for each lane k of hits: the lanes of hits on its ellipsoid. Once a
    // bounce, for every light's bundles (close_lanes()).
    static void lanes_on_one_ellipsoid(Bounce& b, unsigned hits) {
        for (unsigned left = hits; left != 0;) {
            const std::uint32_t on = b.hit[lowest_bit(left)].ellipsoid;
            unsigned group = 0;
            for (unsigned m = left; m != 0; m &= m - 1)
                group |= b.hit[lowest_bit(m)].ellipsoid == on ? 1U << lowest_bit(m) : 0U;
            for (unsigned m = group; m != 0; m &= m - 1) b.same[lowest_bit(m)] = group;
            left &= ~group;
        }
    }

    // Light li's terms where it reaches the lanes' points: their light rays, then their
    // shadow rays as bundles (Bvh::occluded() for lanes), then add_light().
    void add_light_lanes(Bounce& b, const HitLanes& h, std::size_t li,
                         const unsigned (&in_shell)[LightShells<Real>::kMax]) const {
        const Vec3<Q> light = Vec3<Q>::from(tracer_.light_position(li));
        LightRay<Q> r[kChunks];
        unsigned facing = 0;     // with a light ray to try
        unsigned own_clear = 0;  // whose own ellipsoid cannot block their shadow ray (seen from outside)
        for (int i = 0; i < kChunks; ++i) {
            if (part(h.lightable, i) == 0) continue;
            const Chunk& c = b.chunk[i];
            r[i] = light_ray(c.surface, light);
            facing |= static_cast<unsigned>(r[i].faces << (i * kChunk));
            own_clear |= static_cast<unsigned>(
                leaves_own_ellipsoid<Real>(c.surface.scaled_length, r[i].distance, r[i].n_dot_l, c.abs_c)
                << (i * kChunk));
        }
        facing &= h.lightable, own_clear &= static_cast<unsigned>(~h.inside);
        // This light's shells, for the lanes they hold, then a bundle's own ellipsoid
        // after them (set in place: a copy of the shells' list per bundle, read whole
        // just after its last entry was written, stalled on the store).
        ClearedLanes cleared;
        for (unsigned m = shells_.of_light(li); m != 0; m &= m - 1)
            cleared.add(shells_.ellipsoid(lowest_bit(m)), in_shell[lowest_bit(m)] & h.hits);
        const int shells = cleared.count;
        unsigned blocked = 0;
        for (unsigned left = facing; left != 0;) {
            const unsigned bundle = close_lanes(b, left);  // on one ellipsoid, or one lane
            left &= ~bundle;
            const std::uint32_t on = b.hit[lowest_bit(bundle)].ellipsoid;
            cleared.count = shells;
            cleared.add(on, own_clear & bundle);
            std::uint32_t blocker = hints_.load(on, li);
            blocked |=
                tracer_.geometry().occluded(b.point, tracer_.light_position(li), bundle, blocker, cleared);
            hints_.store(on, li, blocker);
        }
        const Vec3<Q> intensity = Vec3<Q>::from(tracer_.light_intensity(li));
        for (int i = 0; i < kChunks; ++i) {
            const LaneBits shown = part(facing & ~blocked, i);
            Chunk& c = b.chunk[i];
            if (shown != 0) add_light(c.colour, c.surface, r[i], intensity, c.finish, shown);
        }
    }

    // Chunk i's lanes of a lane set, as its own lanes 0 to kChunk - 1.
    static LaneBits part(LaneBits lanes, int i) { return lanes_from<kChunk>(lanes, i * kChunk); }

    // A bundle for the first of lanes: the lanes on its ellipsoid, when there are at
    // least kBundleLanes of them and their points lie within its smallest diameter of
    // each other (a tile seen on a sphere, or on the same side of a thin one), else the
    // first lane alone (say, reflected rays landing far apart on a floor, whose bundle
    // would sweep the scene). Measured (callgrind, sphereflakes 4 and 5): bundles of 2
    // or 3 rays cost more than the rays alone.
    static constexpr int kBundleLanes = 4;
    unsigned close_lanes(const Bounce& b, unsigned lanes) const {
        const int first = lowest_bit(lanes);
        const unsigned bundle = b.same[first] & lanes;
        if (bit_count(bundle) < kBundleLanes) return 1U << first;
        using C = AtLeastDouble<Real>;
        C lo[3], hi[3];
        bounds_of(b.point, bundle, lo, hi);
        C scales[3];
        abs_scales(tracer_.geometry().ellipsoid(b.hit[first].ellipsoid), scales);
        const C diameter = 2 * smallest_of(scales);
        const bool close =
            hi[0] - lo[0] <= diameter && hi[1] - lo[1] <= diameter && hi[2] - lo[2] <= diameter;
        return close ? bundle : 1U << first;
    }

    const Tracer& tracer_;
    LightShells<Real> shells_;                                    // the ellipsoids that hold a light
    BlockerHints hints_;                                          // where each shadow query starts
    std::uint8_t background_row_[kBytesPerPixel * kSpanColumns];  // a span's row of BACK's bytes
};

}  // namespace rt
