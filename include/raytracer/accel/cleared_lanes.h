// What a shadow query's caller knows: which ellipsoids cannot block which of its rays.
#pragma once

#include <cstdint>

namespace rt {

// Ellipsoids that a shadow query's caller knows cannot block some of its rays, each with
// those rays' lanes (bit k for lane k; bit 0 for a query of one ray): the ellipsoid a
// point lies on, seen from outside (leaves_own_ellipsoid(), exact_culling.h), and shells
// that hold both a point and the light (light_shells.h). The query skips them there.
struct ClearedLanes {
    static constexpr int kMax = 5;  // the ellipsoid a point lies on and LightShells::kMax shells
    std::uint32_t ellipsoid[kMax] = {};
    unsigned lanes[kMax] = {};
    int count = 0;

    void add(std::uint32_t i, unsigned cleared) {
        if (cleared != 0 && count < kMax) ellipsoid[count] = i, lanes[count++] = cleared;
    }
    // The lanes for which ellipsoid i is cleared.
    unsigned of(std::uint32_t i) const {
        unsigned cleared = 0;
        for (int j = 0; j < count; ++j) cleared |= ellipsoid[j] == i ? lanes[j] : 0U;
        return cleared;
    }
    // The same with each ellipsoid i as number[i] (the tree's leaf order).
    template <typename Numbers>
    ClearedLanes renumbered(const Numbers& number) const {
        ClearedLanes r = *this;
        for (int j = 0; j < count; ++j) r.ellipsoid[j] = number[ellipsoid[j]];
        return r;
    }
    // Lane k's entries, as bit 0: for lane k's ray on its own.
    ClearedLanes lane(int k) const {
        ClearedLanes one;
        for (int j = 0; j < count; ++j) one.add(ellipsoid[j], (lanes[j] >> k) & 1U);
        return one;
    }
};

}  // namespace rt
