#include "raytracer/large_pages.h"

#include <cstdint>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace rt {

void advise_large_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::size_t kHugePage = std::size_t{2} << 20;
    // The whole huge pages inside: from the first boundary at or after data.
    const std::size_t skip = (kHugePage - reinterpret_cast<std::uintptr_t>(data) % kHugePage) % kHugePage;
    // Fewer than two: the advice would split the mapping for little gain.
    if (bytes < skip + 2 * kHugePage) return;
    // Advice only: where the kernel has no huge pages to give, the pages stay small.
    (void)::madvise(static_cast<char*>(data) + skip, (bytes - skip) / kHugePage * kHugePage, MADV_HUGEPAGE);
#endif
}

}  // namespace rt
