#include "diff_picture.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

#include "ambiguous_pixels.h"
#include "pass_rule.h"

namespace grade {
namespace {

constexpr int kGap = 4;              // grey columns between the panels
constexpr int kRingRadius = 10;      // the ring drawn around each unexplained pixel, 2 pixels wide,
                                     // so that it survives a browser's scaling down
constexpr long long kMaxRings = 64;  // more than this, and the red alone shows where they are

struct Canvas {
    rt::Image& image;
    void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) const {
        if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
        const std::size_t at = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                    static_cast<std::size_t>(x));
        image.rgb[at] = r;
        image.rgb[at + 1] = g;
        image.rgb[at + 2] = b;
    }
    void copy(const rt::Image& from, int left) const {
        for (int y = 0; y < from.height; ++y)
            for (int x = 0; x < from.width; ++x) {
                const std::size_t at =
                    3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(from.width) +
                         static_cast<std::size_t>(x));
                set(left + x, y, from.rgb[at], from.rgb[at + 1], from.rgb[at + 2]);
            }
    }
    // A square ring around (cx, cy), clipped to the columns [first, end), drawn only
    // where bare(x, y): over no mark of another pixel.
    template <typename Bare>
    void ring(int cx, int cy, int first, int end, Bare bare) const {
        const auto dot = [&](int x, int y) {
            if (x >= first && x < end && bare(x, y)) set(x, y, 255, 0, 255);
        };
        for (int r = kRingRadius - 1; r <= kRingRadius; ++r) {
            for (int d = -r; d <= r; ++d) {
                dot(cx + d, cy - r);
                dot(cx + d, cy + r);
                dot(cx - r, cy + d);
                dot(cx + r, cy + d);
            }
        }
    }
};

}  // namespace

rt::Image difference_picture(const std::string& key_name, const rt::Image& key, const rt::Image& got) {
    rt::Image picture;
    // Three panels side by side, and a ring's reach past them: wider than an int can
    // say, no picture (as for no key).
    if (key.width > (std::numeric_limits<int>::max() - 2 * kGap - kRingRadius) / 3) return picture;
    picture.width = 3 * key.width + 2 * kGap;
    picture.height = key.height;
    picture.rgb.assign(3 * static_cast<std::size_t>(picture.width) * static_cast<std::size_t>(picture.height),
                       128);
    const Canvas canvas{picture};
    canvas.copy(key, 0);
    canvas.copy(got, key.width + kGap);

    const int left = 2 * (key.width + kGap);
    const std::vector<AmbiguousPixel> ambiguous = ambiguous_pixels_of(key_name);
    std::vector<std::pair<int, int>> unexplained;
    for (int y = 0; y < key.height; ++y) {
        for (int x = 0; x < key.width; ++x) {
            const std::size_t at = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(key.width) +
                                        static_cast<std::size_t>(x));
            int largest = 0;
            const PixelVerdict verdict = pixel_verdict(key, got, x, y, ambiguous, largest);
            if (verdict == PixelVerdict::kSame) {
                const int grey =
                    (key.rgb[at] + key.rgb[at + 1] + key.rgb[at + 2]) / 12;  // a quarter of the mean
                canvas.set(left + x, y, static_cast<std::uint8_t>(grey), static_cast<std::uint8_t>(grey),
                           static_cast<std::uint8_t>(grey));
            } else if (verdict == PixelVerdict::kTruncationStep) {
                canvas.set(left + x, y, 0, 0, 160);
            } else if (verdict == PixelVerdict::kAmbiguous) {
                canvas.set(left + x, y, 255, 255, 0);
            } else {
                canvas.set(left + x, y, static_cast<std::uint8_t>(std::min(255, 128 + 2 * largest)), 0, 0);
                unexplained.emplace_back(x, y);
            }
        }
    }
    const auto bare = [&](int x, int y) {
        int largest = 0;
        return y >= 0 && y < key.height &&
               pixel_verdict(key, got, x - left, y, ambiguous, largest) == PixelVerdict::kSame;
    };
    if (static_cast<long long>(unexplained.size()) <= kMaxRings)
        for (const auto& [x, y] : unexplained) canvas.ring(left + x, y, left, left + key.width, bare);
    return picture;
}

}  // namespace grade
