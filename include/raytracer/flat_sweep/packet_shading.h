// The flat sweep's packets, members of PacketTracer (packet_tracer.h) defined here: the colours of up
// to kPacket hits on one ellipsoid (hit_colours()), the lanes one light reaches, their shadow
// rays tested together (lit_lanes()), and their mirrored rays' nearest hits found together
// (nearest_hits()) and shaded in packets again (reflections()). Each lane gets the
// reference's bytes for its pixel (whitted.h; docs/speed.md says why for each shortcut).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "raytracer/accel/intersect_lanes.h"
#include "raytracer/accel/shadow_prefilter.h"
#include "raytracer/bit_scan.h"
#include "raytracer/compiler.h"
#include "raytracer/finish_lanes.h"
#include "raytracer/flat_sweep/hit_packet.h"
#include "raytracer/flat_sweep/packet_tracer.h"
#include "raytracer/lanes.h"

namespace rt {

// The nearest hits of N rays (kPacket, or fewer lanes) with t > min_t, ray k from
// (ox, oy, oz)[k] along (dx, dy, dz)[k], as the reference finds them
// (BruteForce::closest(), every ellipsoid in increasing order): index[k] is the
// ellipsoid (kNoEllipsoid for none), t[k] its root, inside[k] whether the far root was
// taken.
//
// WHY: one culling pass over the bounding spheres for all rays
// (SphereBounds::candidate_lanes()), and each ellipsoid some ray may hit intersected
// for all lanes at once (intersect_lanes()), in vector instructions. Each lane gets
// the roots intersect() gives, for exactly the ellipsoids its own culling leaves,
// taken in increasing order by the reference's rule: the same hit, t and flag.
template <typename Real>
template <int N>
void PacketTracer<Real>::nearest_hits(const Real* ox, const Real* oy, const Real* oz, const Real* dx,
                                      const Real* dy, const Real* dz, Real min_t, TraceScratch<Real>& scratch,
                                      std::uint32_t* index, Real* t, bool* inside) const {
    std::uint32_t* lanes = scratch.lanes.data();
    // The ellipsoids that some ray may hit, in increasing order.
    const std::uint32_t* some_ray = scratch.candidates.data();
    const std::size_t count = bounds_.template candidate_lanes<N>(
        ox, oy, oz, dx, dy, dz, lanes, scratch.candidates.data(), scratch.cone_misses.data());
    min_t = visible_beyond(min_t);  // as in BruteForce::closest()
    Real best[N], found[N], far_root[N];
    for (int k = 0; k < N; ++k) best[k] = 0, found[k] = 0, far_root[k] = 0, index[k] = kNoEllipsoid;
    for (std::size_t a = 0; a < count; ++a) {
        const std::uint32_t i = some_ray[a];
        const std::uint32_t set = lanes[i];
        Real hit[N], near[N], far[N], take[N], listed[N];
        intersect_lanes<N>(ellipsoids_[i], ox, oy, oz, dx, dy, dz, hit, near, far);
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) listed[k] = (set & kLaneBits<N>.bit[k]) != 0 ? Real(1) : Real(0);
        // visible_root(): inside = !(near > min_t); t = inside ? far : near; taken when
        // t > min_t and nothing nearer was found. (Products of 0/1 masks: with bools and
        // && GCC 12 vectorises the loop too, but the heavy scene took 77.5 against 76.9
        // ms, one thread, medians of 31.)
        RT_VECTOR_LOOP
        for (int k = 0; k < N; ++k) {
            const Real beyond = near[k] > min_t ? Real(1) : Real(0);
            const Real root = beyond != 0 ? near[k] : far[k];
            const Real nearer = found[k] == 0 ? Real(1) : (root < best[k] ? Real(1) : Real(0));
            const Real taken = listed[k] * hit[k] * (root > min_t ? Real(1) : Real(0)) * nearer;
            take[k] = taken;
            best[k] = taken != 0 ? root : best[k];
            far_root[k] = taken != 0 ? Real(1) - beyond : far_root[k];
            found[k] = taken != 0 ? Real(1) : found[k];
        }
        for (int k = 0; k < N; ++k) index[k] = take[k] != 0 ? std::uint32_t(i) : index[k];
    }
    for (int k = 0; k < N; ++k) t[k] = best[k], inside[k] = far_root[k] != 0;
}

// Where a packet's points on ellipsoid i lie, for the shadow rays of every light: a ball
// around them, for LightCones::packet(); and the lanes whose points lie within the
// ellipsoid for Enclosures, once for all lights (the mirror room's points are on it, so
// within it for every light it encloses).
template <typename Real>
struct PacketTracer<Real>::PacketPlace {
    typename LightCones<C>::Ball ball;
    std::uint64_t self_within = 0;
};

template <typename Real>
template <int N>
typename PacketTracer<Real>::PacketPlace PacketTracer<Real>::packet_place(const HitPacket<Real, N>& p,
                                                                          std::uint32_t i) const {
    PacketPlace place;
    place.ball = LightCones<C>::template ball<N>(p.px, p.py, p.pz);
    if (enclosures_.encloses_a_light(i))
        place.self_within = enclosures_.template points_within<N>(p.px, p.py, p.pz, i, kLaneBits<N>.bit);
    return place;
}

// For each light first + b of a batch (b < size) with lit_any[b]: sets batch[b].lit to the
// lanes of packet p (on ellipsoid i) with the light in front that no ellipsoid shadows,
// and lit_any[b] to whether there are any (else the sums are skipped). Set: the width
// of the scene's ellipsoid sets (set_words()).
template <typename Real>
template <int N, typename Set>
void PacketTracer<Real>::shadow_batch(const HitPacket<Real, N>& p, const PacketPlace& place, std::uint32_t i,
                                      std::size_t first, std::size_t size, LightLanes<Real, N>* batch,
                                      bool* lit_any, TraceScratch<Real>& scratch) const {
    // Per light, the ellipsoids that some segment from the packet's ball to it may meet
    // (independent chains, which overlap), then the lanes each of them shadows.
    const Set every = Set::first(ellipsoids_.size());
    Set may_block[kLightBatch];
    for (std::size_t b = 0; b < size; ++b) {
        const std::size_t li = first + b;
        if (!lit_any[b]) continue;
        may_block[b] =
            culling_tables_ ? light_cones_.packet(li, lights_[li].position, place.ball, every) : every;
    }
    for (std::size_t b = 0; b < size; ++b)
        if (lit_any[b])
            lit_any[b] =
                lit_lanes<N, Set>(p, batch[b], i, first + b, may_block[b], place.self_within, scratch) != 0;
}

// The colours (Whitted::shade(), whitted.h) of up to N rays that hit ellipsoid i, ray k
// from (ox, oy, oz)[k] along (dx, dy, dz)[k] at t[k] (hit_packet.h): the same
// operations lane by lane; shadow rays are tested for all lanes at once
// (lit_lanes()), what the mirrored rays hit is found for all lanes at once
// (nearest_hits()), and the mirrored rays are shaded in packets again, grouped by the
// ellipsoid they hit.
template <typename Real>
template <int N>
void PacketTracer<Real>::hit_colours(std::uint32_t i, int count, const Real* ox, const Real* oy,
                                     const Real* oz, const Real* dx, const Real* dy, const Real* dz,
                                     const Real* t, const bool* inside, int reflections_left,
                                     TraceScratch<Real>& scratch, V* colours) const {
    const SurfaceConstants<Real>& surface = surfaces_[i];
    const Ellipsoid<Real>& e = ellipsoids_[i];
    const bool mirror = reflects(e, reflections_left);
    if (surface.no_lighting && !mirror) {  // the colour is the ambient term
        for (int k = 0; k < count; ++k) colours[k] = surface.ambient_term;
        return;
    }
    HitPacket<Real, N> p;
    p.load(count, ox, oy, oz, dx, dy, dz, t, inside);
    p.surface(e, surface.ambient_term);
    if (!surface.no_lighting) {
        const auto finish = every_lane<HitPacket<Real, N>::kChunk>(finish_of(e));
        PacketPlace place;  // set with p.facing_light(), for the first light that faces a lane
        bool facing = false;
        // The lights in batches: first each light's terms (independent chains of
        // square roots and divisions, which overlap), then the shadow rays, then the
        // sums in the order of the lights.
        LightLanes<Real, N> batch[kLightBatch];
        bool lit_any[kLightBatch];
        for (std::size_t first = 0; first < lights_.size(); first += kLightBatch) {
            const std::size_t size = std::min(kLightBatch, lights_.size() - first);
            bool faces_any = false;
            for (std::size_t b = 0; b < size; ++b) {  // false: behind every ray's point
                lit_any[b] = p.light(lights_[first + b].position, batch[b]);
                faces_any = faces_any || lit_any[b];
            }
            if (!faces_any) continue;
            if (!facing) p.facing_light(e), place = packet_place(p, i), facing = true;
            if (ellipsoids_.size() <= NarrowSet::kCapacity)
                shadow_batch<N, NarrowSet>(p, place, i, first, size, batch, lit_any, scratch);
            else
                shadow_batch<N, WideSet>(p, place, i, first, size, batch, lit_any, scratch);
            for (std::size_t b = 0; b < size; ++b) {
                // No lane lit: the sums would keep every lane's colour (selects).
                if (!lit_any[b]) continue;
                p.add_light(batch[b], lights_[first + b].intensity, finish);
            }
        }
    }
    if (mirror) reflections(p, e.kr, reflections_left, scratch);
    for (int k = 0; k < count; ++k) colours[k] = {p.r[k], p.g[k], p.b[k]};
}

// The lanes of a packet with light li in front (l.front) that the light reaches, their
// shadow rays tested together: sets l.lit to them and returns them.
//
// WHY: each candidate ellipsoid is tried on all lanes at once with blocked_lanes()
// (shadow_prefilter.h: the prefilter in vector instructions, and intersect() only for
// the rare lanes it is unsure about). A lane is shadowed when SOME ellipsoid blocks its
// segment, and each test gives intersect()'s exact answer, so the order of the tries
// does not matter; a lane is left untried only for ellipsoids that cannot block it
// (outside its segment's cone, LightCones::lanes(), or ruled out for the whole packet,
// below; the self ellipsoid where self_clear; those that enclose light and point), so
// each lane gets the unculled renderer's boolean: the same bytes.
// may_block: the ellipsoids that can block some lane at all (LightCones::packet() for
// the packet's ball; all of them without culling_tables_), in a set of Set's width.
// self_within: the lanes whose points Enclosures::points_within() ellipsoid self.
template <typename Real>
template <int N, typename Set>
std::uint64_t PacketTracer<Real>::lit_lanes(const HitPacket<Real, N>& p, LightLanes<Real, N>& l,
                                            std::uint32_t self, std::size_t li, Set may_block,
                                            std::uint64_t self_within, TraceScratch<Real>& scratch) const {
    using Bits = std::uint64_t;  // bit k for lane k
    // Selects of these constants rather than shifts by k: GCC then vectorises the
    // loops below.
    constexpr const Bits(&kLane)[N] = kLaneBits<N>.bit;
    // Which lanes have the light in front. Lanes from p.count on repeat the last ray:
    // they are never waiting.
    const Bits front = l.front & ((Bits(1) << p.count) - 1);
    // The own ellipsoid cannot block the lanes where it encloses the light and the
    // point (self_within, computed once a packet: packet_place()), nor those where
    // self_clear holds (computed only where that matters).
    Bits self_free = enclosures_.light_within(li, self) ? self_within : 0;
    if (may_block.contains(self) && (front & ~self_free) != 0) self_free |= p.self_clear(l);
    if ((front & ~self_free) == 0) may_block.erase(self);
    if (may_block.empty()) {  // no ellipsoid can block any lane
        l.lit = front;
        return front;
    }
    // Per lane, point - light = -(L - P) exactly.
    Real fx[N], fy[N], fz[N];
    for (int k = 0; k < N; ++k) fx[k] = -l.tx[k], fy[k] = -l.ty[k], fz[k] = -l.tz[k];
    // Per candidate j, the lanes whose segment may meet it (all first: independent
    // vector tests, which overlap).
    Bits meets[Set::kCapacity];
    Bits reached = 0;
    may_block.for_each([&](std::size_t j) {
        reached |= meets[j] =
            culling_tables_ ? light_cones_.template lanes<N>(li, j, fx, fy, fz, l.distance, kLane) : ~Bits(0);
    });
    Bits waiting = front;  // lanes not yet known to be shadowed
    if ((reached & front) == 0) {
        l.lit = front;
        return front;
    }
    // Ellipsoid j against the waiting lanes whose segment may meet it; clears their
    // bits when blocked.
    auto try_ellipsoid = [&](std::size_t j) {
        Bits lanes = waiting & meets[j];
        if (j == self)
            lanes &= ~self_free;
        else if (lanes != 0)
            lanes &= ~enclosures_.template contains_segments<N>(p.px, p.py, p.pz, li, j, kLane);
        if (lanes == 0) return;
        const Bits blocked = blocked_lanes<N>(ellipsoids_[j], p.px, p.py, p.pz, l.tx, l.ty, l.tz, lanes);
        if (blocked == 0) return;
        waiting &= ~blocked;
        scratch.blocker_hints[li] = static_cast<std::uint32_t>(j);
    };
    // The last blocker of this light first (neighbouring pixels share their shadows),
    // then the others in increasing order, until every lane is shadowed.
    const std::uint32_t last = scratch.blocker_hints[li];
    if (last != kNoEllipsoid && may_block.contains(last)) {
        try_ellipsoid(last);
        may_block.erase(last);
    }
    may_block.for_each_while(try_ellipsoid, [&] { return waiting != 0; });
    // Lit: the light in front and no blocker found.
    l.lit = waiting;
    return waiting;
}

// The mirrored rays of a packet (Whitted::shade()); adds seen * kr to each lane's colour.
template <typename Real>
template <int N>
void PacketTracer<Real>::reflections(HitPacket<Real, N>& p, Real kr, int reflections_left,
                                     TraceScratch<Real>& scratch) const {
    Real mx[N], my[N], mz[N];
    p.mirror(mx, my, mz);
    std::uint32_t next[N];
    Real next_t[N];
    bool next_inside[N];
    // What each mirrored ray hits (lanes from p.count on repeat the last ray). A
    // reflected ray that hits nothing returns black, unlike an eye ray.
    nearest_hits<N>(p.px, p.py, p.pz, mx, my, mz, Real(kReflectedRayMinT), scratch, next, next_t,
                    next_inside);
    V seen[N] = {};
    using Bits = std::uint64_t;
    constexpr const Bits(&kLane)[N] = kLaneBits<N>.bit;
    const Bits counted = (Bits(1) << p.count) - 1;  // p.count <= N <= 32
    Bits waiting = 0;  // the lanes whose mirrored rays hit something not yet shaded
    RT_VECTOR_LOOP
    for (int k = 0; k < N; ++k) waiting |= next[k] != kNoEllipsoid ? kLane[k] : 0;
    waiting &= counted;
    while (waiting != 0) {
        const int k = lowest_bit(waiting);
        // The lanes whose mirrored rays hit the same ellipsoid, as one packet.
        const std::uint32_t target = next[k];
        Bits same = 0;
        RT_VECTOR_LOOP
        for (int j = 0; j < N; ++j) same |= next[j] == target ? kLane[j] : 0;
        same &= waiting;
        waiting &= ~same;
        if (same == counted) {  // all of them (the usual case): the packet's own arrays
            hit_colours<N>(target, p.count, p.px, p.py, p.pz, mx, my, mz, next_t, next_inside,
                           reflections_left - 1, scratch, seen);
            break;
        }
        int lane[N], n = 0;
        Real gox[N], goy[N], goz[N], gdx[N], gdy[N], gdz[N], gt[N];
        bool gin[N];
        for (Bits rest = same; rest != 0; rest &= rest - 1) {
            const int j = lowest_bit(rest);
            lane[n] = j;
            gox[n] = p.px[j], goy[n] = p.py[j], goz[n] = p.pz[j];
            gdx[n] = mx[j], gdy[n] = my[j], gdz[n] = mz[j], gt[n] = next_t[j], gin[n] = next_inside[j];
            ++n;
        }
        V group[N];
        packet_width(n, [&](auto width) {
            hit_colours<decltype(width)::value>(target, n, gox, goy, goz, gdx, gdy, gdz, gt, gin,
                                                reflections_left - 1, scratch, group);
        });
        for (int j = 0; j < n; ++j) seen[lane[j]] = group[j];
    }
    for (int k = 0; k < p.count; ++k) p.add(k, seen[k] * kr);
}

}  // namespace rt
