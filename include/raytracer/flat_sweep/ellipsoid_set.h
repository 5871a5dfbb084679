// A set of the flat sweep's ellipsoids, a bit each: the blockers a shadow ray of a
// packet may meet (light_cones.h), intersected and walked in increasing order, after the
// light's last blocker (PacketTracer::lit_lanes()).
//
// WHY two widths: the sets are made per packet and light, so they live on the stack and
// each operation is a loop over their words, unrolled. A scene of up to 64 ellipsoids
// (the course's) takes one word; with the widest set the heavy scene rendered 3% slower.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raytracer/bit_scan.h"
#include "raytracer/flat_sweep/render_flat_sweep.h"

namespace rt {

template <std::size_t Words>
class EllipsoidSet {
public:
    static constexpr std::size_t kWords = Words;
    static constexpr std::size_t kCapacity = 64 * Words;

    // Ellipsoids 0 to count - 1 (count <= kCapacity).
    static EllipsoidSet first(std::size_t count) {
        EllipsoidSet s;
        for (std::size_t w = 0; w < kWords; ++w) {
            const std::size_t below = w * 64;
            s.word_[w] = count >= below + 64 ? ~std::uint64_t(0)
                         : count > below     ? (std::uint64_t(1) << (count - below)) - 1
                                             : 0;
        }
        return s;
    }
    // The set stored as `count` words (at most kWords) from `words` on, and back.
    static EllipsoidSet from_words(const std::uint64_t* words, std::size_t count) {
        EllipsoidSet s;
        for (std::size_t w = 0; w < kWords; ++w) s.word_[w] = w < count ? words[w] : 0;
        return s;
    }
    void to_words(std::uint64_t* words, std::size_t count) const {
        for (std::size_t w = 0; w < count && w < kWords; ++w) words[w] = word_[w];
    }

    bool contains(std::size_t j) const { return ((word_[j / 64] >> (j % 64)) & 1U) != 0; }
    void insert(std::size_t j) { word_[j / 64] |= std::uint64_t(1) << (j % 64); }
    void erase(std::size_t j) { word_[j / 64] &= ~(std::uint64_t(1) << (j % 64)); }
    // Adds the ellipsoids first + k for each bit k of `bits` (all within first's word).
    void insert_bits(std::size_t first, std::uint64_t bits) { word_[first / 64] |= bits << (first % 64); }

    bool empty() const {
        std::uint64_t any = 0;
        for (std::uint64_t w : word_) any |= w;
        return any == 0;
    }
    bool operator==(const EllipsoidSet& other) const {
        std::uint64_t differ = 0;
        for (std::size_t w = 0; w < kWords; ++w) differ |= word_[w] ^ other.word_[w];
        return differ == 0;
    }
    EllipsoidSet& operator&=(const EllipsoidSet& other) {
        for (std::size_t w = 0; w < kWords; ++w) word_[w] &= other.word_[w];
        return *this;
    }

    // Calls visit(j) for each member j in increasing order, while keep_going() holds
    // (asked before each).
    template <typename Visit, typename KeepGoing>
    void for_each_while(Visit visit, KeepGoing keep_going) const {
        for (std::size_t w = 0; w < kWords; ++w)
            for (std::uint64_t rest = word_[w]; rest != 0; rest &= rest - 1) {
                if (!keep_going()) return;
                visit(w * 64 + static_cast<std::size_t>(lowest_bit(rest)));
            }
    }
    template <typename Visit>
    void for_each(Visit visit) const {
        for_each_while(visit, [] { return true; });
    }

private:
    std::uint64_t word_[kWords] = {};
};

// The flat sweep's two widths: scenes of up to 64 ellipsoids, and every scene it renders.
using NarrowSet = EllipsoidSet<1>;
using WideSet = EllipsoidSet<(kFlatSweepEllipsoids + 63) / 64>;

// The words of a set of a scene of n ellipsoids (at most WideSet::kCapacity).
inline std::size_t set_words(std::size_t n) { return n <= NarrowSet::kCapacity ? 1 : WideSet::kWords; }

}  // namespace rt
