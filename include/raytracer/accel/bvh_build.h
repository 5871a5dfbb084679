// The tree of bvh.h, built in two steps. First a binary tree, top-down over the items'
// boxes with binned surface-area-heuristic splits (I. Wald, "On fast Construction of
// SAH-based Bounding Volume Hierarchies", IEEE Symposium on Interactive Ray Tracing
// 2007): per node, the boxes' centres are put into kBins bins along their widest axis
// and the cheapest of the kBins - 1 planes between bins is taken, O(N) per level,
// O(N log N) in all; a node of at most kBins items is sorted instead, and each plane
// between two of its items tried. Then collapse() makes nodes of Width children of it,
// with small subtrees as leaves.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "raytracer/accel/run_beside.h"
#include "raytracer/large_pages.h"

namespace rt {

template <typename C>
struct BuildBox {
    C lo[3], hi[3];

    void grow(const BuildBox& b) {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], b.lo[a]), hi[a] = std::max(hi[a], b.hi[a]);
    }
    C half_area() const {
        const C x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        return x * y + y * z + z * x;
    }
};

// What the tree is built over: a box, its centre, a value kept as the minimum over each
// subtree (bvh.h's guard) and one kept as the maximum (the margin per unit of distance
// its box needs past the guard), and the caller's index.
template <typename C>
struct BuildItem {
    BuildItem() {}  // NOLINT: not zeroed, so that a list of them is first touched where each is set
    BuildBox<C> box;
    C centre[3];
    C guard, rate;
    std::uint32_t index;
};

template <typename C>
struct BuildNode {
    BuildBox<C> box;
    C guard;                  // the minimum of the items' guards
    C rate;                   // the maximum of the items' rates
    std::uint32_t first = 0;  // a leaf's first item; an inner node's first child
    std::uint32_t count = 0;  // a leaf's items; 0 for an inner node, whose children are first, first + 1
};

template <typename C>
class BinaryTreeBuilder {
public:
    static constexpr std::size_t kLeafItems = 8;  // at most, where the SAH prefers a leaf
    static constexpr int kBins = 16;
    static constexpr int kMedianDepth = 32;  // and below, median splits: depth < 32 + log2(N)
    // The SAH's costs: a box test, and a ray/ellipsoid test (divisions and a square root).
    // Measured, not derived: an item cost of 2 makes leaves of one or two ellipsoids and
    // 8-wide nodes a third full (random 100k, read and prepared: 67.5 MiB); 0.75 makes
    // larger leaves and 62 MiB at the same speed within 2% (0.5: 51 MiB, but random 1k
    // and sphereflake 3 6% slower).
    static constexpr double kBoxCost = 1, kItemCost = 0.75;

    // Where threads > 1, the halves of the first node (in build order) whose halves are
    // large enough to pay for a thread (about 0.1 ms to start) and the smaller at least
    // 1 / kBalance of the node are built on two threads: the same tree, as each half is
    // built alone either way, in the same order. That is the root in the scale scenes,
    // and a node below it where the root splits off a few far or huge ellipsoids. Halves
    // of 2,000 against 20,000: random 10k read and prepared (RES 1 1) 10.8 -> 9.6 ms,
    // sphereflake 4 7.9 -> 7.3 ms (whole process, interleaved, medians of 21).
    static constexpr std::size_t kItemsPerThread = 2000, kBalance = 3;

    // Reorders items into leaf order; nodes[0] is the root.
    LargeVector<BuildNode<C>> build(LargeVector<BuildItem<C>>& items, unsigned threads = 1) {
        threads_ = threads;
        nodes_.clear();
        if (items.empty()) return nodes_;
        nodes_.reserve(2 * items.size());
        nodes_.emplace_back();
        grow(items, 0, 0, items.size(), 0);
        return std::move(nodes_);
    }

private:
    void grow(LargeVector<BuildItem<C>>& items, std::size_t node, std::size_t first, std::size_t last,
              int depth) {
        // The node's box and guard, and the box of the items' centres, in one pass.
        BuildNode<C> n;
        n.box = items[first].box, n.guard = items[first].guard, n.rate = items[first].rate;
        BuildBox<C> centres;
        for (int a = 0; a < 3; ++a) centres.lo[a] = centres.hi[a] = items[first].centre[a];
        for (std::size_t k = first + 1; k < last; ++k) {
            const BuildItem<C>& item = items[k];
            n.box.grow(item.box), n.guard = std::min(n.guard, item.guard),
                                  n.rate = std::max(n.rate, item.rate);
            for (int a = 0; a < 3; ++a)
                centres.lo[a] = std::min(centres.lo[a], item.centre[a]),
                centres.hi[a] = std::max(centres.hi[a], item.centre[a]);
        }
        const std::size_t middle =
            last - first <= 1 ? last : split(items, first, last, n.box, centres, depth);
        if (middle == last) {
            n.first = static_cast<std::uint32_t>(first), n.count = static_cast<std::uint32_t>(last - first);
            nodes_[node] = n;
            return;
        }
        n.first = static_cast<std::uint32_t>(nodes_.size());
        nodes_[node] = n;
        nodes_.emplace_back(), nodes_.emplace_back();
        if (threads_ > 1 && worth_a_thread(middle - first, last - middle)) {
            grow_beside(items, n.first, first, middle, last, depth + 1);
            return;
        }
        grow(items, n.first, first, middle, depth + 1);
        grow(items, n.first + 1, middle, last, depth + 1);
    }

    // Whether the halves of a node are both large enough to pay for a thread, and near
    // enough in size that the two threads finish at about the same time.
    static bool worth_a_thread(std::size_t below, std::size_t above) {
        const std::size_t smaller = std::min(below, above);
        return smaller >= kItemsPerThread && kBalance * smaller >= below + above;
    }

    // The two halves of a node: [first, middle) here, [middle, last) on another thread
    // into a list of its own, which then follows this one's, as it would have. Only once:
    // below it each thread builds alone.
    void grow_beside(LargeVector<BuildItem<C>>& items, std::uint32_t children, std::size_t first,
                     std::size_t middle, std::size_t last, int depth) {
        threads_ = 1;
        BinaryTreeBuilder right;
        right.nodes_.reserve(2 * (last - middle));
        right.nodes_.emplace_back();
        run_beside([&] { right.grow(items, 0, middle, last, depth); },
                   [&] { grow(items, children, first, middle, depth); });
        // Node j > 0 of the right half goes to base + j - 1; its root to the slot kept.
        const auto base = static_cast<std::uint32_t>(nodes_.size());
        for (std::size_t j = 0; j < right.nodes_.size(); ++j) {
            BuildNode<C> node = right.nodes_[j];
            if (node.count == 0) node.first = node.first - 1 + base;
            if (j == 0)
                nodes_[children + 1] = node;
            else
                nodes_.push_back(node);
        }
    }

    // Where to split items [first, last) (their box, their centres' box), or last for a
    // leaf: the binned SAH's best plane along the centres' widest axis; the median along
    // it where the SAH finds none but the items are too many for a leaf, and from
    // kMedianDepth on.
    std::size_t split(LargeVector<BuildItem<C>>& items, std::size_t first, std::size_t last,
                      const BuildBox<C>& box, const BuildBox<C>& centres, int depth) const {
        const std::size_t n = last - first;
        int widest = 0;
        for (int a = 1; a < 3; ++a)
            if (centres.hi[a] - centres.lo[a] > centres.hi[widest] - centres.lo[widest]) widest = a;
        if (depth >= kMedianDepth) return median(items, first, last, widest);

        // Along the centres' widest axis only: a third of the work, and on the scale
        // scenes the same render time within noise (docs/speed.md).
        if (!(centres.hi[widest] > centres.lo[widest]))
            return n <= kLeafItems ? last : median(items, first, last, widest);
        if (n <= std::size_t{kBins}) return sorted_split(items, first, last, box, widest);
        const int best_bin = best_plane(items, first, last, box, centres, widest);
        if (best_bin == 0) return n <= kLeafItems ? last : median(items, first, last, widest);
        const C scale = C(kBins) / (centres.hi[widest] - centres.lo[widest]);
        const auto middle =
            std::partition(items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(last),
                           [&](const BuildItem<C>& item) {
                               return bin_of(item.centre[widest], centres.lo[widest], scale) < best_bin;
                           });
        const auto m = static_cast<std::size_t>(middle - items.begin());
        return m == first || m == last ? median(items, first, last, widest) : m;
    }

    // split() for a node of at most kBins items: the items sorted along axis a and each
    // plane between two of them tried. Most nodes are this small, and for them setting
    // up and sweeping the bins cost more than the sort (measured in docs/speed.md).
    static std::size_t sorted_split(LargeVector<BuildItem<C>>& items, std::size_t first, std::size_t last,
                                    const BuildBox<C>& box, int a) {
        std::sort(items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(last),
                  [a](const BuildItem<C>& x, const BuildItem<C>& y) { return x.centre[a] < y.centre[a]; });
        const std::size_t n = last - first;
        C right_area[kBins];  // of items [first + k, last)
        BuildBox<C> grown = items[last - 1].box;
        for (std::size_t k = n - 1; k > 0; --k)
            right_area[k] = grown.half_area(), grown.grow(items[first + k - 1].box);
        std::size_t best = 0;
        C least = std::numeric_limits<C>::infinity();
        grown = items[first].box;
        for (std::size_t k = 1; k < n; ++k) {  // the plane before item first + k
            const C sum = C(k) * grown.half_area() + C(n - k) * right_area[k];
            if (sum < least) least = sum, best = k;
            grown.grow(items[first + k].box);
        }
        if (beats_leaf(least, box, n)) return first + best;
        return n <= kLeafItems ? last : first + n / 2;  // the median, as sorted
    }

    // The bin of a centre along an axis; NaN and overflow go to the end bins.
    static int bin_of(C centre, C lo, C scale) {
        const C x = (centre - lo) * scale;
        return x >= C(kBins - 1) ? kBins - 1 : x > 0 ? static_cast<int>(x) : 0;
    }

    // The cheapest plane between bins along axis a if it costs less than a leaf: the
    // number of bins below it; else 0.
    static int best_plane(const LargeVector<BuildItem<C>>& items, std::size_t first, std::size_t last,
                          const BuildBox<C>& box, const BuildBox<C>& centres, int a) {
        const C scale = C(kBins) / (centres.hi[a] - centres.lo[a]);
        BuildBox<C> bins[kBins];
        std::size_t counts[kBins] = {};
        for (std::size_t k = first; k < last; ++k) {
            const int b = bin_of(items[k].centre[a], centres.lo[a], scale);
            if (counts[b]++ == 0)
                bins[b] = items[k].box;
            else
                bins[b].grow(items[k].box);
        }
        // From the right: the half area and count of bins [b, kBins).
        C right_area[kBins];
        std::size_t right_count[kBins];
        BuildBox<C> grown{};
        std::size_t count = 0;
        auto take = [&](int b) {
            if (counts[b] == 0) return;
            if (count == 0)
                grown = bins[b];
            else
                grown.grow(bins[b]);
            count += counts[b];
        };
        for (int b = kBins - 1; b > 0; --b) {
            take(b);
            right_area[b] = count > 0 ? grown.half_area() : 0, right_count[b] = count;
        }
        int best = 0;
        C least = std::numeric_limits<C>::infinity();
        count = 0;
        for (int b = 0; b + 1 < kBins; ++b) {
            take(b);
            if (count == 0 || right_count[b + 1] == 0) continue;
            const C sum = C(count) * grown.half_area() + C(right_count[b + 1]) * right_area[b + 1];
            if (sum < least) least = sum, best = b + 1;
        }
        return best > 0 && beats_leaf(least, box, last - first) ? best : 0;
    }

    // Whether splitting a node of n items in this box into two whose item counts times
    // half areas sum to `sum` costs less, by the SAH, than a leaf of them. The cost grows
    // with the sum: a split is chosen by its sum, then costed once (one division).
    static bool beats_leaf(C sum, const BuildBox<C>& box, std::size_t n) {
        return C(kBoxCost) + C(kItemCost) * sum / box.half_area() < C(kItemCost) * C(n);
    }

    static std::size_t median(LargeVector<BuildItem<C>>& items, std::size_t first, std::size_t last, int a) {
        const std::size_t middle = first + (last - first) / 2;
        std::nth_element(
            items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(middle),
            items.begin() + std::ptrdiff_t(last),
            [a](const BuildItem<C>& x, const BuildItem<C>& y) { return x.centre[a] < y.centre[a]; });
        return middle;
    }

    LargeVector<BuildNode<C>> nodes_;
    unsigned threads_ = 1;
};

// A child of a wide node: the wide node `first` when count is 0, else the leaf of items
// [first, first + count).
struct WideChild {  // trivial: the traversal's stack is not initialised
    std::uint32_t first, count;
};
// Width children; their boxes (side 0 the low corner, 1 the high one), by axis and lane,
// and guards: a child may be culled for a ray whose origin lies within this max-norm
// distance of each of its corners (bvh.h), and past it by its box grown by rate times
// that distance (margin_per_reach()).
template <typename C, int Width>
struct WideNode {
    C box[2][3][Width];
    C guard[Width];
    C rate[Width];
    WideChild child[Width];
    unsigned used;  // bit k for each child k in use
};

// A binary subtree of at most this many items, met where a wide node has no lane left
// for its children, becomes one leaf rather than a wide node of its own. The binary SAH
// makes leaves of one or two items, which left half the wide nodes with two children:
// on random 100k, 29,900 nodes of 520 bytes, and 9,117 with this rule (15.5 -> 4.7 MB),
// at the same render speed within noise on the scale scenes (docs/speed.md).
constexpr std::uint32_t kSmallSubtree = 4;

namespace detail {
// Whether binary subtree b holds at most `most` items; if so, leaf is them all (a
// subtree's items are contiguous: the build partitions them in place).
template <typename C>
bool small_subtree(const LargeVector<BuildNode<C>>& binary, std::uint32_t b, std::uint32_t most,
                   WideChild& leaf) {
    const BuildNode<C>& node = binary[b];
    if (node.count > 0) {
        leaf = {node.first, node.count};
        return node.count <= most;
    }
    WideChild below, above;
    if (!small_subtree(binary, node.first, most, below) ||
        !small_subtree(binary, node.first + 1, most - below.count, above))
        return false;
    leaf = {below.first, below.count + above.count};
    return true;
}

// The wide node for binary inner node b, appended to nodes: its children, where an inner
// one with the largest box is replaced by its own two children until there are Width
// (the "pull up the largest" rule of Embree's BVH4 builders).
template <int Width, typename C>
std::uint32_t collapse_node(const LargeVector<BuildNode<C>>& binary, std::uint32_t b,
                            LargeVector<WideNode<C, Width>>& nodes) {
    std::uint32_t lanes[Width] = {binary[b].first, binary[b].first + 1};
    int used = 2;
    while (used < Width) {
        int widest = -1;
        for (int k = 0; k < used; ++k)
            if (binary[lanes[k]].count == 0 &&
                (widest < 0 || binary[lanes[k]].box.half_area() > binary[lanes[widest]].box.half_area()))
                widest = k;
        if (widest < 0) break;
        const std::uint32_t inner = lanes[widest];
        lanes[widest] = binary[inner].first;
        lanes[used++] = binary[inner].first + 1;
    }
    const auto index = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    WideNode<C, Width> node{};
    for (int k = 0; k < Width; ++k) {  // unused lanes: an empty box, not in used
        for (int a = 0; a < 3; ++a)
            node.box[0][a][k] = std::numeric_limits<C>::max(), node.box[1][a][k] = -node.box[0][a][k];
        node.guard[k] = std::numeric_limits<C>::max(), node.rate[k] = 0;
    }
    node.used = (1U << used) - 1;
    for (int k = 0; k < used; ++k) {
        const BuildNode<C>& child = binary[lanes[k]];
        for (int a = 0; a < 3; ++a) node.box[0][a][k] = child.box.lo[a], node.box[1][a][k] = child.box.hi[a];
        node.guard[k] = child.guard, node.rate[k] = child.rate;
        WideChild leaf;
        if (child.count > 0)
            node.child[k] = {child.first, child.count};
        else if (small_subtree(binary, lanes[k], kSmallSubtree, leaf))
            node.child[k] = leaf;
        else
            node.child[k] = {collapse_node<Width>(binary, lanes[k], nodes), 0};
    }
    nodes[index] = node;
    return index;
}
}  // namespace detail

// The binary tree (non-empty; root binary[0]) as wide nodes of Width children, into
// nodes: the root, a leaf or nodes[first].
template <int Width, typename C>
WideChild collapse(const LargeVector<BuildNode<C>>& binary, LargeVector<WideNode<C, Width>>& nodes) {
    if (binary[0].count > 0) return {binary[0].first, binary[0].count};
    // At most one wide node per inner binary node: reserved (pages that are never
    // written cost no memory), so that the list is not copied as it grows.
    nodes.reserve(binary.size() / 2);
    return {detail::collapse_node<Width>(binary, 0, nodes), 0};
}

}  // namespace rt
