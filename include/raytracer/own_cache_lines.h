// Working memory that shares no cache line with any other allocation.
//
// WHY: a thread's working memory is written for every packet of rays, and an allocation
// made beside it in the heap (the scene's tables, another thread's working memory) can
// share its first or last cache line. Every write then takes that line from the other
// core, and the other thread's next read of its own data there waits for it: on the
// heavy scene with two threads the flat sweep's sphere culling spent a third of its time
// on such loads (perf), and its working memory on lines of its own took the whole
// process from 46 to 41 ms (perf stat, medians of 21).
#pragma once

#include <algorithm>
#include <cstddef>
#include <new>
#include <vector>

namespace rt {

// An allocator whose blocks start on a cache line and fill whole lines.
template <typename T>
struct OwnCacheLines {
    using value_type = T;
    // A cache line on the x86-64 and ARM cores this runs on (C++17's
    // hardware_destructive_interference_size is not in every standard library).
    static constexpr std::size_t kLine = 64;
    static constexpr std::size_t kAlign = std::max(kLine, alignof(T));

    OwnCacheLines() = default;
    template <typename U>
    explicit OwnCacheLines(const OwnCacheLines<U>& /*unused*/) {}

    T* allocate(std::size_t n) {
        const std::size_t bytes = (n * sizeof(T) + kAlign - 1) / kAlign * kAlign;
        return static_cast<T*>(::operator new (bytes, std::align_val_t{kAlign}));
    }
    void deallocate(T* p, std::size_t /*n*/) { ::operator delete (p, std::align_val_t{kAlign}); }
    template <typename U>
    bool operator==(const OwnCacheLines<U>& /*unused*/) const {
        return true;
    }
    template <typename U>
    bool operator!=(const OwnCacheLines<U>& /*unused*/) const {
        return false;
    }
};

template <typename T>
using OwnLinesVector = std::vector<T, OwnCacheLines<T>>;

}  // namespace rt
