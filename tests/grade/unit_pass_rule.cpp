// The pass rule of SPEC section 7: which differing pixels a scene may have, and what the
// grader reports about the others, in words and in the difference picture.
#include <array>
#include <cstdint>
#include <string>

#include "../check.h"
#include "ambiguous_pixels.h"
#include "diff_picture.h"
#include "pass_rule.h"

namespace {

rt::Image grey(int width, int height, std::uint8_t level) {
    rt::Image image;
    image.width = width;
    image.height = height;
    image.rgb.assign(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), level);
    return image;
}

void set(rt::Image& image, int x, int y, int channel, std::uint8_t value) {
    image.rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + x) + channel] =
        value;
}

}  // namespace

TEST(identical_images_pass) {
    const grade::Judgement j = grade::judge("keyShadow", grey(8, 8, 9), grey(8, 8, 9));
    CHECK(j.passed() && j.differing == 0);
}

TEST(one_level_in_every_channel_everywhere_fails) {  // rounding instead of truncating
    const grade::Judgement j = grade::judge("keyShadow", grey(6, 5, 100), grey(6, 5, 101));
    CHECK(!j.passed() && j.too_many_steps() && j.differing == 30 && j.truncation_steps == 30);
    CHECK(j.unexplained == 0 && j.unexplained_box.empty());
}

TEST(a_dozen_pixels_one_level_off_pass_and_thirteen_fail) {
    rt::Image got = grey(20, 20, 50);
    for (int x = 0; x < 12; ++x) set(got, x, 4, x % 3, x % 2 == 0 ? 51 : 49);
    CHECK(grade::judge("keyShadow", grey(20, 20, 50), got).passed());
    set(got, 0, 5, 1, 51);
    const grade::Judgement j = grade::judge("keyShadow", grey(20, 20, 50), got);
    CHECK(!j.passed() && j.truncation_steps == 13 && j.unexplained == 0);
}

TEST(an_image_of_another_size_is_not_compared) {
    const grade::Judgement j = grade::judge("keyShadow", grey(4, 4, 9), grey(2, 2, 9));
    CHECK(!j.passed() && j.unexplained == 16);
}

TEST(two_levels_in_one_channel_of_one_pixel_fails_and_is_located) {
    rt::Image got = grey(10, 10, 50);
    set(got, 7, 3, 2, 52);
    set(got, 2, 5, 0, 51);  // allowed
    const grade::Judgement j = grade::judge("keyShadow", grey(10, 10, 50), got);
    CHECK(!j.passed());
    CHECK(j.differing == 2 && j.truncation_steps == 1 && j.unexplained == 1 && j.largest_difference == 2);
    CHECK(j.unexplained_box.left == 7 && j.unexplained_box.right == 7);
    CHECK(j.unexplained_box.top == 3 && j.unexplained_box.bottom == 3);
    CHECK(j.first_unexplained.size() == 1 && j.first_unexplained[0].x == 7 && j.first_unexplained[0].y == 3);
    CHECK(j.first_unexplained[0].key[2] == 50 && j.first_unexplained[0].got[2] == 52);
    CHECK(!j.first_unexplained[0].ambiguous);
}

TEST(a_known_ambiguous_pixel_may_show_its_other_outcome_but_only_in_its_own_key) {
    // keyShadow (400, 150): the eye ray tangent to s1, named in SPEC section 7; the key
    // has the hit, the other outcome is the miss (BACK, white).
    rt::Image key = grey(600, 600, 255);
    set(key, 400, 150, 0, 23), set(key, 400, 150, 1, 0), set(key, 400, 150, 2, 0);
    rt::Image got = grey(600, 600, 255);
    const grade::Judgement j = grade::judge("keyShadow", key, got);
    CHECK(j.passed() && j.ambiguous == 1 && j.truncation_steps == 0);
    CHECK(!grade::judge("keyAmbient", key, got).passed());
    set(got, 400, 150, 1, 254);  // a truncation step from the other outcome
    CHECK(grade::judge("keyShadow", key, got).passed());
    set(got, 400, 150, 1, 253);  // two levels from it, and from the key: neither outcome
    const grade::Judgement two = grade::judge("keyShadow", key, got);
    CHECK(!two.passed() && two.unexplained == 1 && two.ambiguous == 0);
    CHECK(two.first_unexplained.size() == 1 && two.first_unexplained[0].ambiguous);
    CHECK((two.first_unexplained[0].other == std::array<std::uint8_t, 3>{255, 255, 255}));
    set(got, 400, 150, 1, 255);
    set(got, 401, 150, 0, 253);  // its neighbour is not ambiguous: 2 levels fail
    const grade::Judgement beside = grade::judge("keyShadow", key, got);
    CHECK(!beside.passed() && beside.ambiguous == 1 && beside.unexplained == 1);
    // The report's "largest" is the failing pixel's 2, not the allowed one's 255.
    CHECK(beside.largest_difference == 255 && beside.largest_failing == 2);
}

TEST(every_known_ambiguous_pixel_passes_with_its_other_outcome_and_fails_with_a_third_colour) {
    for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels()) {
        const rt::Image key = grey(600, 600, 100);  // two levels or more from each colour below
        rt::Image got = key;
        for (int c = 0; c < 3; ++c) set(got, p.x, p.y, c, p.other[static_cast<std::size_t>(c)]);
        const grade::Judgement j = grade::judge(p.key, key, got);
        CHECK(j.passed() && j.ambiguous == 1);
        for (int c = 0; c < 3; ++c)
            set(got, p.x, p.y, c, static_cast<std::uint8_t>(p.other[static_cast<std::size_t>(c)] ^ 0x40));
        CHECK(!grade::judge(p.key, key, got).passed());
    }
}

TEST(the_table_holds_the_pixels_spec_section_7_names) {
    const auto has = [](const char* key, int x, int y) {
        for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels_of(key))
            if (p.x == x && p.y == y) return true;
        return false;
    };
    CHECK(has("keyShadow", 400, 150) && has("keyShadow", 400, 225) && has("keyShadow", 450, 200));
    CHECK(has("keyIllum", 240, 345) && has("keyIllum", 360, 345));
    for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels())
        CHECK(p.x >= 0 && p.x < 600 && p.y >= 0 && p.y < 600 && std::string(p.reason).size() > 20);
}

TEST(the_first_unexplained_pixels_are_listed_in_reading_order_and_counted_beyond) {
    const grade::Judgement j = grade::judge("keyAmbient", grey(20, 20, 200), grey(20, 20, 0));
    CHECK(j.unexplained == 400 && j.first_unexplained.size() == grade::Judgement::kShown);
    CHECK(j.first_unexplained[1].x == 1 && j.first_unexplained[1].y == 0);
    CHECK(j.unexplained_box.right == 19 && j.unexplained_box.bottom == 19);
}

// The difference panel (the third, from 2 (width + 4)): each unexplained pixel red and
// ringed in magenta, the ring never over another differing pixel's mark.
TEST(the_difference_picture_rings_unexplained_pixels_over_no_other_mark) {
    const rt::Image key = grey(60, 40, 50);
    rt::Image got = key;
    set(got, 20, 20, 0, 90);  // unexplained
    set(got, 30, 20, 0, 90);  // unexplained, where the first one's ring passes (radius 10)
    set(got, 20, 30, 0, 51);  // a truncation step, where it passes too
    const rt::Image picture = grade::difference_picture("keyShadow", key, got);
    const int left = 2 * (key.width + 4);
    const auto at = [&](int x, int y) {
        const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(picture.width) +
                                   static_cast<std::size_t>(left + x));
        return std::array<int, 3>{picture.rgb[i], picture.rgb[i + 1], picture.rgb[i + 2]};
    };
    CHECK((at(20, 20) == std::array<int, 3>{208, 0, 0}));    // red, brighter by 2 a level
    CHECK((at(30, 20) == std::array<int, 3>{208, 0, 0}));    // not the first one's ring
    CHECK((at(20, 30) == std::array<int, 3>{0, 0, 160}));    // dark blue, not the ring
    CHECK((at(10, 20) == std::array<int, 3>{255, 0, 255}));  // the ring itself
    CHECK((at(20, 10) == std::array<int, 3>{255, 0, 255}));
}

// Three panels wider than an int: no picture, rather than an overflow (the pixels are
// not read: a key that large is not made here).
TEST(no_difference_picture_wider_than_an_int) {
    rt::Image huge;
    huge.width = 715'827'882;  // 3 x this + the gaps passes 2^31 - 1
    huge.height = 1;
    CHECK(grade::difference_picture("keyShadow", huge, huge).rgb.empty());
}
