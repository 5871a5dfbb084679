#include "raytracer/large_pages.h"

#include <cstdint>

#include "raytracer/compiler.h"

#ifdef __linux__
#include <sys/mman.h>
#endif

// Blocks of whole huge pages on Linux, but not under AddressSanitizer, whose checks then
// cover the large blocks too.
#if defined(__linux__) && defined(MADV_HUGEPAGE) && !defined(RT_UNDER_ASAN)
#define RT_WHOLE_PAGES 1
#endif

namespace rt {

namespace {
#ifdef RT_WHOLE_PAGES
constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t whole_pages(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

// Mapped with a huge page to spare, then the parts before the first boundary and after
// the block unmapped: the block holds no more address space than its pages (an aligned
// operator new keeps the spare too: reading a 100,000-sphere file then needed 44-52 MB
// of address space instead of 36-40).
void* map_whole_pages(std::size_t bytes) {
    if (bytes > SIZE_MAX - 2 * kHugePage) throw std::bad_array_new_length();
    const std::size_t whole = whole_pages(bytes);
    void* const mapped =
        ::mmap(nullptr, whole + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const std::size_t head = (kHugePage - reinterpret_cast<std::uintptr_t>(mapped) % kHugePage) % kHugePage;
    char* const block = static_cast<char*>(mapped) + head;
    if (head > 0) (void)::munmap(mapped, head);
    (void)::munmap(block + whole, kHugePage - head);  // never empty: head < kHugePage
    (void)::madvise(block, whole, MADV_HUGEPAGE);
    return block;
}
#endif
}  // namespace

bool large_blocks_on_huge_pages() {
#ifdef RT_WHOLE_PAGES
    return true;
#else
    return false;
#endif
}

void* allocate_large(std::size_t bytes) {
#ifdef RT_WHOLE_PAGES
    if (bytes >= kLargeBlock) return map_whole_pages(bytes);
#endif
    return ::operator new(bytes);
}

void deallocate_large(void* block, [[maybe_unused]] std::size_t bytes) noexcept {
#ifdef RT_WHOLE_PAGES
    if (bytes >= kLargeBlock) {
        (void)::munmap(block, whole_pages(bytes));
        return;
    }
#endif
    ::operator delete(block);
}

}  // namespace rt
