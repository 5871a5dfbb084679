// Working memory on cache lines of its own (own_cache_lines.h): each block starts on a
// cache line, and no other allocation made beside it, however small, shares one of its
// lines.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "check.h"
#include "raytracer/own_cache_lines.h"

namespace {

constexpr std::uintptr_t kLine = rt::OwnCacheLines<char>::kLine;

struct alignas(128) Wide {
    double x[3];
};

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

// Whether bytes [a, a + a_size) and [b, b + b_size) touch a common cache line.
bool share_a_line(std::uintptr_t a, std::size_t a_size, std::uintptr_t b, std::size_t b_size) {
    const std::uintptr_t a_first = a / kLine, a_last = (a + a_size - 1) / kLine;
    const std::uintptr_t b_first = b / kLine, b_last = (b + b_size - 1) / kLine;
    return a_first <= b_last && b_first <= a_last;
}

}  // namespace

TEST(blocks_start_on_a_cache_line) {
    for (std::size_t n = 1; n <= 70; ++n) {
        const rt::OwnLinesVector<std::uint32_t> small(n);
        const rt::OwnLinesVector<double> doubles(n);
        const rt::OwnLinesVector<Wide> wide(n);
        CHECK_EQ(address(small.data()) % kLine, 0U);
        CHECK_EQ(address(doubles.data()) % kLine, 0U);
        CHECK_EQ(address(wide.data()) % alignof(Wide), 0U);
    }
}

// Small blocks of the plain heap made between blocks of own lines (as a thread's working
// memory is made beside the scene's tables) never share a line with them; plain blocks
// made the same way do share lines with each other (what the allocator is for).
TEST(no_other_allocation_shares_a_line) {
    std::vector<rt::OwnLinesVector<std::uint32_t>> own;
    std::vector<std::unique_ptr<char[]>> plain;
    std::vector<std::size_t> plain_sizes;
    for (std::size_t k = 0; k < 200; ++k) {
        own.emplace_back(1 + k % 13);
        plain_sizes.push_back(1 + (k * 7) % 40);
        plain.emplace_back(new char[plain_sizes.back()]);
    }
    int shared = 0, plain_shared = 0;
    for (std::size_t i = 0; i < own.size(); ++i) {
        const std::size_t own_bytes = own[i].capacity() * sizeof(std::uint32_t);
        for (std::size_t j = 0; j < plain.size(); ++j) {
            shared +=
                share_a_line(address(own[i].data()), own_bytes, address(plain[j].get()), plain_sizes[j]);
            if (j != i)
                plain_shared += share_a_line(address(plain[i].get()), plain_sizes[i], address(plain[j].get()),
                                             plain_sizes[j]);
        }
        for (std::size_t j = 0; j < i; ++j)
            shared += share_a_line(address(own[i].data()), own_bytes, address(own[j].data()),
                                   own[j].capacity() * sizeof(std::uint32_t));
    }
    CHECK_EQ(shared, 0);
    CHECK(plain_shared > 0);
}

// A count whose bytes, rounded up to whole lines, would wrap around is refused, as
// std::allocator refuses it, not turned into a small block.
TEST(a_count_too_large_is_refused) {
    bool refused = false;
    try {
        rt::OwnCacheLines<std::uint32_t> lines;
        (void)lines.allocate(std::numeric_limits<std::size_t>::max() / 4);
    } catch (const std::bad_array_new_length&) {
        refused = true;
    }
    CHECK(refused);
}
