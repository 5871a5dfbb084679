// The known ambiguous pixels' two outcomes, derived from the course scenes: the reference
// (whitted.h over brute_force.h, in double) gives each such pixel the key's bytes, and
// rays a billionth of a pixel to each side give the key's bytes or the table's other
// outcome, and nothing else. The nudge is far above double's rounding of the ray (about
// 1e-16 of it) and far below what moves a colour by a level, so it only decides the side.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "../check.h"
#include "ambiguous_pixels.h"
#include "raytracer/image.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/whitted.h"

namespace {

using Bytes3 = std::array<std::uint8_t, 3>;
using Reference = rt::Whitted<double, rt::BruteForce<double>>;

struct Course {
    rt::Scene scene;
    rt::Image key;
    std::unique_ptr<Reference> reference;
};

// The scene and key of a key's name ("keyShadow": testShadow.txt and keyShadow.ppm).
const Course& course(const std::string& key_name) {
    static std::map<std::string, Course> loaded;
    Course& c = loaded[key_name];
    if (!c.reference) {
        const std::string folder = RAYTRACER_COURSE_TESTS;
        c.scene = rt::load_scene(folder + "/scenes/test" + key_name.substr(3) + ".txt", 1);
        std::string error;
        CHECK(rt::read_ppm(folder + "/keys/" + key_name + ".ppm", c.key, error));
        c.reference = std::make_unique<Reference>(
            c.scene, rt::BruteForce<double>(rt::make_ellipsoids<double>(c.scene)));
    }
    return c;
}

// CHECK with the pixel named in the message.
void expect(bool holds, int line, const std::string& what) {
    if (!holds) check::fail(__FILE__, line, what);
}

Bytes3 key_bytes(const rt::Image& key, int x, int y) {
    const std::size_t at = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(key.width) + x);
    return {key.rgb[at], key.rgb[at + 1], key.rgb[at + 2]};
}

}  // namespace

TEST(each_ambiguous_pixel_has_the_key_outcome_and_the_table_outcome_and_no_third) {
    for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels()) {
        const Course& c = course(p.key);
        Reference::Scratch scratch = c.reference->make_scratch();
        const double x = c.reference->column_x(p.x), y = c.reference->row_y(p.y);
        const Bytes3 key = key_bytes(c.key, p.x, p.y);
        Bytes3 centre;
        c.reference->pixel(x, y, centre.data(), scratch);
        const std::string where =
            std::string(p.key) + " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
        expect(centre == key, __LINE__, where + ": the reference does not give the key's bytes");
        expect(p.other != key, __LINE__, where + ": the other outcome is the key's");
        const double nudge = 1e-9 * (c.scene.right - c.scene.left) / c.scene.columns;
        std::set<Bytes3> outcomes;
        for (int k = 0; k < 16; ++k) {
            const double angle = 2 * 3.141592653589793 * k / 16;
            Bytes3 bytes;
            c.reference->pixel(x + nudge * std::cos(angle), y + nudge * std::sin(angle), bytes.data(),
                               scratch);
            outcomes.insert(bytes);
        }
        expect(outcomes == std::set<Bytes3>{key, p.other}, __LINE__,
               where + ": the nudged rays' outcomes differ from the table's");
    }
}
