// The pass rule of SPEC section 7, per scene: every pixel that differs from the key must be
// explainable, either as a truncation step (each channel off by at most one level) or as
// one of the key's known ambiguous pixels showing its other outcome, within a truncation
// step (ambiguous_pixels.h). The truncation steps must be few: a value that lands within
// rounding of a whole level is rare (3 pixels of the 12 keys' 4,320,000 for our renderer),
// where rounding instead of truncating (SPEC section 6) puts half the pixels one level
// off. Anything else fails.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ambiguous_pixels.h"
#include "raytracer/image.h"

namespace grade {

// The most pixels off by one level that a scene may have: the dozen that SPEC section 7
// allows in all 12 keys, per scene here (the course's marks are per scene).
inline constexpr long long kMaxTruncationSteps = 12;

// What the rule makes of one pixel.
enum class PixelVerdict { kSame, kTruncationStep, kAmbiguous, kUnexplained };

// The rule for pixel (x, y) of got against its key, given the key's ambiguous pixels;
// largest: its largest channel difference, in levels.
PixelVerdict pixel_verdict(const rt::Image& key, const rt::Image& got, int x, int y,
                           const std::vector<AmbiguousPixel>& ambiguous, int& largest);

struct PixelDifference {
    int x = 0, y = 0;  // column, row from the top
    std::uint8_t key[3] = {0, 0, 0};
    std::uint8_t got[3] = {0, 0, 0};
    bool ambiguous = false;               // a known ambiguous pixel, with
    std::array<std::uint8_t, 3> other{};  // its other outcome
};

struct Box {
    int left = 0, top = 0, right = -1, bottom = -1;  // inclusive; empty when right < left
    bool empty() const { return right < left; }
    void add(int x, int y);
};

struct Judgement {
    long long differing = 0;         // pixels with any channel different
    long long truncation_steps = 0;  // of those, off by at most one level in each channel
    long long ambiguous = 0;         // of those, known ambiguous pixels showing the other outcome
    long long unexplained = 0;       // the rest: each fails the scene
    int largest_difference = 0;      // in levels, over all differing pixels
    int largest_failing = 0;         // in levels, over all but the known ambiguous ones
    Box unexplained_box;             // where the unexplained pixels lie
    std::vector<PixelDifference> first_unexplained;  // in reading order, at most kShown
    bool too_many_steps() const { return truncation_steps > kMaxTruncationSteps; }
    bool passed() const { return unexplained == 0 && !too_many_steps(); }
    static constexpr std::size_t kShown = 5;
};

// Compares an image with its key of the same size (else every pixel counts as unexplained); key_name is the
// key's file stem
// ("keyShadow"), which selects its ambiguous pixels.
Judgement judge(const std::string& key_name, const rt::Image& key, const rt::Image& got);

}  // namespace grade
