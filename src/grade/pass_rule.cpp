#include "pass_rule.h"

#include <algorithm>
#include <cstdlib>

#include "ambiguous_pixels.h"

namespace grade {

void Box::add(int x, int y) {
    if (empty()) {
        left = right = x;
        top = bottom = y;
        return;
    }
    left = std::min(left, x);
    right = std::max(right, x);
    top = std::min(top, y);
    bottom = std::max(bottom, y);
}

PixelVerdict pixel_verdict(const rt::Image& key, const rt::Image& got, int x, int y,
                           const std::vector<AmbiguousPixel>& ambiguous, int& largest) {
    const std::size_t at =
        3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(key.width) + static_cast<std::size_t>(x));
    largest = 0;
    for (std::size_t k = at; k < at + 3; ++k) largest = std::max(largest, std::abs(key.rgb[k] - got.rgb[k]));
    if (largest == 0) return PixelVerdict::kSame;
    if (largest <= 1) return PixelVerdict::kTruncationStep;
    // A known ambiguous pixel may show the other outcome (within a truncation step of it).
    const bool other_outcome = std::any_of(ambiguous.begin(), ambiguous.end(), [&](const AmbiguousPixel& p) {
        if (p.x != x || p.y != y) return false;
        for (std::size_t c = 0; c < 3; ++c)
            if (std::abs(p.other[c] - got.rgb[at + c]) > 1) return false;
        return true;
    });
    return other_outcome ? PixelVerdict::kAmbiguous : PixelVerdict::kUnexplained;
}

Judgement judge(const std::string& key_name, const rt::Image& key, const rt::Image& got) {
    Judgement j;
    if (got.width != key.width || got.height != key.height || got.rgb.size() != key.rgb.size()) {
        j.differing = j.unexplained = static_cast<long long>(key.width) * key.height;  // not comparable
        return j;
    }
    const std::vector<AmbiguousPixel> ambiguous = ambiguous_pixels_of(key_name);
    for (int y = 0; y < key.height; ++y) {
        for (int x = 0; x < key.width; ++x) {
            int largest = 0;
            const PixelVerdict verdict = pixel_verdict(key, got, x, y, ambiguous, largest);
            if (verdict == PixelVerdict::kSame) continue;
            ++j.differing;
            j.largest_difference = std::max(j.largest_difference, largest);
            if (verdict != PixelVerdict::kAmbiguous) j.largest_failing = std::max(j.largest_failing, largest);
            if (verdict == PixelVerdict::kTruncationStep) {
                ++j.truncation_steps;
            } else if (verdict == PixelVerdict::kAmbiguous) {
                ++j.ambiguous;
            } else {
                ++j.unexplained;
                j.unexplained_box.add(x, y);
                if (j.first_unexplained.size() < Judgement::kShown) {
                    const std::size_t at =
                        3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(key.width) +
                             static_cast<std::size_t>(x));
                    PixelDifference d;
                    d.x = x;
                    d.y = y;
                    for (std::size_t c = 0; c < 3; ++c) {
                        d.key[c] = key.rgb[at + c];
                        d.got[c] = got.rgb[at + c];
                    }
                    for (const AmbiguousPixel& p : ambiguous)
                        if (p.x == x && p.y == y) d.ambiguous = true, d.other = p.other;
                    j.first_unexplained.push_back(d);
                }
            }
        }
    }
    return j;
}

}  // namespace grade
