// Truncation to 8 bits (rt::to_byte, include/raytracer/image.h) in each precision: the
// SPEC's examples, and decimal colours that land exactly on a step.
#include <cmath>
#include "check.h"
#include "raytracer/image.h"

namespace {

template <typename Real>
int byte(double channel) {
    return rt::to_byte(static_cast<Real>(channel));
}

}  // namespace

TEST(the_specs_examples_truncate) {
    CHECK_EQ(byte<double>(0.25), 63);
    CHECK_EQ(byte<double>(0.5), 127);
    CHECK_EQ(byte<double>(1.0), 255);
    CHECK_EQ(byte<double>(2.0), 255);
    CHECK_EQ(byte<double>(0.0), 0);
    CHECK_EQ(byte<double>(-0.5), 0);
    CHECK_EQ(byte<long double>(0.25), 63);
    CHECK_EQ(byte<float>(0.25), 63);
}

// 0.6 is stored just below 0.6 (and 0.2, 0.4, 0.8 just above): every precision must
// give the decimal scene's level, 153, not 152 in long double and 153 in double.
TEST(decimal_steps_give_the_same_level_in_every_precision) {
    for (double v : {0.2, 0.4, 0.6, 0.8}) {
        const int expected = static_cast<int>(std::lround(v * 255));  // 51, 102, 153, 204
        CHECK_EQ(byte<float>(v), expected);
        CHECK_EQ(byte<double>(v), expected);
        CHECK_EQ(byte<long double>(v), expected);
    }
    // A product of scene numbers: Ka 0.3 times AMBIENT 2 is 0.5999999999999999778.
    CHECK_EQ(rt::to_byte(0.3L * 2.0L), 153);
    CHECK_EQ(rt::to_byte(0.3 * 2.0), 153);
}

// Only rounding is forgiven: a millionth of a level below a step is below it.
TEST(a_value_really_below_a_step_is_truncated) {
    CHECK_EQ(byte<double>((153 - 1e-6) / 255.0), 152);
    CHECK_EQ(byte<long double>((153 - 1e-6) / 255.0), 152);
    CHECK_EQ(byte<double>((43 - 4e-4) / 255.0), 42);  // like keyIllum's pixel (430,128)
}
