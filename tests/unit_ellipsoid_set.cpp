// EllipsoidSet (ellipsoid_set.h) against a plain list of members: each operation at the
// edges of its words (63, 64, 127, 128 and the last index), for one word and for the
// widest set, and a walk that stops part-way through a later word.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "check.h"
#include "raytracer/flat_sweep/ellipsoid_set.h"

namespace {

// The members of s in increasing order, as for_each() visits them.
template <typename Set>
std::vector<std::size_t> members(const Set& s) {
    std::vector<std::size_t> out;
    s.for_each([&](std::size_t j) { out.push_back(j); });
    return out;
}

template <typename Set>
void operations_match_a_list() {
    constexpr std::size_t kLast = Set::kCapacity - 1;
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{63}, std::size_t{64},
                                    std::size_t{65}, std::size_t{128}, Set::kCapacity}) {
        if (count > Set::kCapacity) continue;
        const std::vector<std::size_t> got = members(Set::first(count));
        CHECK_EQ(got.size(), count);
        for (std::size_t k = 0; k < got.size(); ++k) CHECK_EQ(got[k], k);
    }
    std::mt19937 g(5);
    for (int round = 0; round < 200; ++round) {
        Set a, b;
        std::vector<bool> in_a(Set::kCapacity), in_b(Set::kCapacity);
        for (std::size_t j : {std::size_t{0}, std::size_t{63}, std::size_t{64}, std::size_t{127},
                              std::size_t{128}, kLast, std::size_t(g() % Set::kCapacity)}) {
            if (j > kLast) continue;
            if (g() % 2) a.insert(j), in_a[j] = true;
            if (g() % 2) b.insert(j), in_b[j] = true;
        }
        // Eight spheres from a multiple of 8 on, as LightCones::packet() adds them.
        const std::size_t first = 8 * (g() % (Set::kCapacity / 8));
        const std::uint64_t eight = g() % 256;
        a.insert_bits(first, eight);
        for (std::size_t k = 0; k < 8; ++k)
            if ((eight >> k) & 1U) in_a[first + k] = true;
        const std::size_t gone = g() % Set::kCapacity;
        a.erase(gone), in_a[gone] = false;
        for (std::size_t j = 0; j < Set::kCapacity; ++j) CHECK_EQ(a.contains(j), bool(in_a[j]));
        Set both = a;
        both &= b;
        std::vector<std::size_t> expected;
        for (std::size_t j = 0; j < Set::kCapacity; ++j)
            if (in_a[j] && in_b[j]) expected.push_back(j);
        CHECK(members(both) == expected);
        CHECK_EQ(both.empty(), expected.empty());
        CHECK(both == both && (both == a) == (members(both) == members(a)));
        // Stored and read back, in its own width.
        std::uint64_t words[Set::kWords];
        a.to_words(words, Set::kWords);
        CHECK(Set::from_words(words, Set::kWords) == a);
        // A walk that stops after `stop` members.
        const std::vector<std::size_t> all = members(a);
        const std::size_t stop = all.empty() ? 0 : g() % all.size();
        std::vector<std::size_t> walked;
        a.for_each_while([&](std::size_t j) { walked.push_back(j); }, [&] { return walked.size() < stop; });
        CHECK(walked == std::vector<std::size_t>(all.begin(), all.begin() + std::ptrdiff_t(stop)));
    }
}

}  // namespace

TEST(one_word_sets_match_a_list) { operations_match_a_list<rt::NarrowSet>(); }
TEST(the_widest_sets_match_a_list) { operations_match_a_list<rt::WideSet>(); }

// A scene stored one word wide reads back into the widest set with its other words empty.
TEST(a_narrow_store_reads_into_a_wide_set) {
    rt::NarrowSet narrow;
    narrow.insert(0), narrow.insert(63);
    std::uint64_t word[1];
    narrow.to_words(word, 1);
    const rt::WideSet wide = rt::WideSet::from_words(word, 1);
    CHECK(members(wide) == (std::vector<std::size_t>{0, 63}));
    CHECK_EQ(rt::set_words(64), std::size_t{1});
    CHECK_EQ(rt::set_words(65), rt::WideSet::kWords);
    CHECK(rt::WideSet::kCapacity >= rt::kFlatSweepEllipsoids);
}
