// Where a shadow query starts (Bvh::occluded()'s blocker): per ellipsoid and light, the
// ellipsoid that last blocked a shadow ray from that ellipsoid's surface to that light.
// Two numberings: the key is the scene's index of the ellipsoid the rays start on (a
// NearestHit's), the hint a position in the tree's leaf order (what occluded() takes).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "raytracer/large_pages.h"
#include "raytracer/reference/spec_rules.h"

namespace rt {

// Points on one ellipsoid mostly lie in the shadow of one other; one hint per light,
// shared by every ellipsoid (as Whitted::Scratch's), fails where a tile's pixels fall on
// several. Against that: random 1k / 10k / 100k 13% / 8% / 9% faster (whole process, 2
// threads, interleaved, medians of 11), 8.9% / 7.6% fewer instructions on random 1k /
// 10k and 1.9% on sphereflake 4 (callgrind, one thread).
//
// One table for all threads, at most kMaxSlots of them: a hint only says where the
// search starts, never what it finds (Bvh::occluded() answers the same from any), so a
// hint that another thread wrote, or one of another pair that shares its slot, costs
// time at most, never a byte. The same holds for the order in which threads write.
class BlockerHints {
public:
    static constexpr std::size_t kMaxSlots = std::size_t{1} << 20;  // 4 MiB

    BlockerHints(std::size_t ellipsoids, std::size_t lights)
        : lights_(lights), slots_(slot_count(ellipsoids * lights)), mask_(slots_.size() - 1) {
        for (auto& s : slots_) s.store(kNoEllipsoid, std::memory_order_relaxed);
    }

    std::uint32_t load(std::uint32_t ellipsoid, std::size_t light) const {
        return slot(ellipsoid, light).load(std::memory_order_relaxed);
    }
    // Writes only a hint that changed, so that threads that agree share its cache line.
    void store(std::uint32_t ellipsoid, std::size_t light, std::uint32_t blocker) const {
        std::atomic<std::uint32_t>& s = slot(ellipsoid, light);
        if (s.load(std::memory_order_relaxed) != blocker) s.store(blocker, std::memory_order_relaxed);
    }

private:
    // A power of two: a slot per pair, up to kMaxSlots.
    static std::size_t slot_count(std::size_t pairs) {
        std::size_t slots = 1;
        while (slots < pairs && slots < kMaxSlots) slots *= 2;
        return slots;
    }
    std::atomic<std::uint32_t>& slot(std::uint32_t ellipsoid, std::size_t light) const {
        return slots_[(std::size_t{ellipsoid} * lights_ + light) & mask_];
    }

    std::size_t lights_;
    mutable LargeVector<std::atomic<std::uint32_t>> slots_;
    std::size_t mask_;  // slots_.size() - 1
};

}  // namespace rt
