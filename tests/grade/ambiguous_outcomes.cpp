// The known ambiguous pixels (ambiguous_pixels.cpp) against the course scenes.
//
// Found: every eye ray of the 12 scenes that is exactly tangent to an ellipsoid beyond
// the near plane, or meets one exactly at t = 1 (on the near plane), decided in exact
// rational arithmetic (exact_disc_mask.h) on the candidates a double prefilter leaves,
// and whose pixel has two outcomes (below): the table lists exactly those, each with its
// reason.
//
// Outcomes: the reference (whitted.h over brute_force.h, in double) gives each such
// pixel the key's bytes, and rays a billionth of a pixel to each side give the key's
// bytes or the table's other outcome, and nothing else. The nudge is far above double's
// rounding of the ray (about 1e-16 of it) and far below what moves a colour by a level,
// so it only decides the side.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "../check.h"
#include "../exact_disc_mask.h"
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

// The distinct bytes of 16 rays a billionth of a pixel around pixel (x, y)'s ray.
std::set<Bytes3> nudged_outcomes(const Course& c, int x, int y) {
    Reference::Scratch scratch = c.reference->make_scratch();
    const double px = c.reference->column_x(x), py = c.reference->row_y(y);
    const double nudge = 1e-9 * (c.scene.right - c.scene.left) / c.scene.columns;
    std::set<Bytes3> outcomes;
    for (int k = 0; k < 16; ++k) {
        const double angle = 2 * 3.141592653589793 * k / 16;
        Bytes3 bytes;
        c.reference->pixel_through(px + nudge * std::cos(angle), py + nudge * std::sin(angle), bytes.data(),
                                   scratch);
        outcomes.insert(bytes);
    }
    return outcomes;
}

// A scene's numbers as written (the exact tests start from the decimals).
struct SceneText {
    std::map<std::string, std::string> view;  // NEAR, LEFT, RIGHT, BOTTOM, TOP
    struct Sphere {
        std::string name;
        std::array<std::string, 3> centre, scale;
    };
    std::vector<Sphere> spheres;
};

SceneText scene_text(const std::string& path) {
    SceneText text;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string keyword;
        fields >> keyword;
        if (keyword == "SPHERE") {
            SceneText::Sphere s;
            fields >> s.name >> s.centre[0] >> s.centre[1] >> s.centre[2] >> s.scale[0] >> s.scale[1] >>
                s.scale[2];
            text.spheres.push_back(s);
        } else if (keyword == "NEAR" || keyword == "LEFT" || keyword == "RIGHT" || keyword == "BOTTOM" ||
                   keyword == "TOP") {
            fields >> text.view[keyword];
        }
    }
    return text;
}

// Whether the point of pixel (c, r) on the near plane lies exactly on the ellipsoid:
// sum (P_i - C_i)^2 / s_i^2 = 1, times (cols rows)^2 s_x^2 s_y^2 s_z^2, in integers once
// every number is a whole multiple of one power of ten.
class NearPlanePoints {
public:
    NearPlanePoints(const SceneText& text, const SceneText::Sphere& sphere, int columns, int rows)
        : columns_(exact::from_int(columns)), rows_(exact::from_int(rows)) {
        using exact::Decimal;
        std::vector<Decimal> all;  // the view's five numbers, then the centre's and the scales' three
        all.reserve(11);
        for (const char* k : {"LEFT", "RIGHT", "BOTTOM", "TOP", "NEAR"})
            all.push_back(exact::parse_decimal(text.view.at(k)));
        for (int i = 0; i < 3; ++i)
            all.push_back(exact::parse_decimal(sphere.centre[static_cast<std::size_t>(i)]));
        for (int i = 0; i < 3; ++i)
            all.push_back(exact::parse_decimal(sphere.scale[static_cast<std::size_t>(i)]));
        int unit = 0;
        for (const Decimal& d : all) unit = std::min(unit, d.exponent);
        std::vector<exact::Integer> n;
        n.reserve(all.size());
        for (const Decimal& d : all) n.push_back(exact::in_units_of_ten(d, unit));
        left_ = n[0], right_ = n[1], bottom_ = n[2], top_ = n[3], near_ = n[4];
        const exact::Integer both = columns_ * rows_;
        std::array<exact::Integer, 3> s2;
        for (std::size_t i = 0; i < 3; ++i) {
            centre_[i] = n[5 + i] * both;
            const exact::Integer si = n[8 + i] * both;
            s2[i] = si * si;
        }
        k_ = {s2[1] * s2[2], s2[0] * s2[2], s2[0] * s2[1]};
        product_ = s2[0] * s2[1] * s2[2];
    }

    bool on_surface(int c, int r) const {
        const std::array<exact::Integer, 3> p = {
            (left_ * columns_ + (right_ - left_) * exact::from_int(c)) * rows_,
            (top_ * rows_ - (top_ - bottom_) * exact::from_int(r)) * columns_, -(near_ * columns_ * rows_)};
        exact::Integer sum;
        for (std::size_t i = 0; i < 3; ++i) {
            const exact::Integer d = p[i] - centre_[i];
            sum = sum + d * d * k_[i];
        }
        return exact::sign(sum - product_) == 0;
    }

private:
    exact::Integer columns_, rows_, left_, right_, bottom_, top_, near_, product_;
    std::array<exact::Integer, 3> centre_, k_;
};

// An ambiguous pixel as the scan finds it: key, x, y, and its reason's words.
using Found = std::tuple<std::string, int, int, std::string>;

struct Scan {
    std::set<Found> found;
    long candidates = 0;  // rays the double prefilter left for the exact test
    long exact = 0;       // of those, exact events
};

// How near the double prefilter lets a ray come to an event and still leave it to the
// exact test: |b^2 - a c| within this of its terms, or the point at t = 1 within this of
// the surface. Double's own rounding there is about 1e-16, so no event is missed; it is
// loose enough that the exact test also meets, and must reject, rays near an event
// (the course scenes have some at 4e-8 and 4e-5).
constexpr double kPrefilter = 1e-4;

// The scene's pixels whose exact eye ray is tangent to an ellipsoid beyond the near plane
// or meets one on it, and whose pixel has two outcomes.
void scan(const std::string& scene_path, const std::string& key_name, Scan& out) {
    const Course& c = course(key_name);
    const SceneText text = scene_text(scene_path);
    const int columns = c.scene.columns, rows = c.scene.rows;
    const exact::CornerRays rays(text.view.at("LEFT"), text.view.at("RIGHT"), text.view.at("BOTTOM"),
                                 text.view.at("TOP"), text.view.at("NEAR"), columns, rows);
    std::vector<exact::EllipsoidForm> forms;
    std::vector<NearPlanePoints> near_points;
    for (const SceneText::Sphere& sphere : text.spheres) {
        forms.emplace_back(sphere.centre, sphere.scale);
        near_points.emplace_back(text, sphere, columns, rows);
    }
    for (int r = 0; r < rows; ++r)
        for (int x = 0; x < columns; ++x) {
            const double d[3] = {c.reference->column_x(x), c.reference->row_y(r), -c.scene.near_plane};
            std::vector<std::string> events;
            for (std::size_t i = 0; i < c.scene.spheres.size(); ++i) {
                const rt::SphereSpec& e = c.scene.spheres[i];
                const double centre[3] = {e.centre.x, e.centre.y, e.centre.z};
                const double scale[3] = {e.scale.x, e.scale.y, e.scale.z};
                double a = 0, b = 0, cc = -1, g = 0;  // g: the point at t = 1 in the unit sphere's space
                for (int k = 0; k < 3; ++k) {
                    const double o = -centre[k] / scale[k], dk = d[k] / scale[k];
                    a += dk * dk, b += o * dk, cc += o * o, g += (o + dk) * (o + dk);
                }
                const double disc = b * b - a * cc, t = -b / a;
                const std::string& name = text.spheres[i].name;
                if (std::abs(disc) <= kPrefilter * (b * b + std::abs(a * cc)) && t > 1 - kPrefilter) {
                    ++out.candidates;
                    if (forms[i].side(rays.exact(x, r)) == 0) events.push_back("tangent to " + name);
                }
                if (std::abs(g - 1) <= kPrefilter) {
                    ++out.candidates;
                    if (near_points[i].on_surface(x, r)) events.push_back("meets " + name);
                }
            }
            out.exact += static_cast<long>(events.size());
            if (!events.empty() && nudged_outcomes(c, x, r).size() > 1)
                for (const std::string& event : events) out.found.insert({key_name, x, r, event});
        }
}

}  // namespace

TEST(each_ambiguous_pixel_has_the_key_outcome_and_the_table_outcome_and_no_third) {
    for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels()) {
        const Course& c = course(p.key);
        Reference::Scratch scratch = c.reference->make_scratch();
        const double x = c.reference->column_x(p.x), y = c.reference->row_y(p.y);
        const Bytes3 key = key_bytes(c.key, p.x, p.y);
        Bytes3 centre;
        c.reference->pixel_through(x, y, centre.data(), scratch);
        const std::string where =
            std::string(p.key) + " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
        expect(centre == key, __LINE__, where + ": the reference does not give the key's bytes");
        int apart = 0;  // levels between the outcomes: more than a truncation step
        for (std::size_t k = 0; k < 3; ++k) apart = std::max(apart, std::abs(p.other[k] - key[k]));
        expect(apart > 1, __LINE__, where + ": the other outcome is within a step of the key's");
        const std::set<Bytes3> outcomes = nudged_outcomes(c, p.x, p.y);
        expect(outcomes == std::set<Bytes3>{key, p.other}, __LINE__,
               where + ": the nudged rays' outcomes differ from the table's");
    }
}

TEST(the_table_lists_exactly_the_exactly_degenerate_eye_rays_with_two_outcomes) {
    Scan all;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(RAYTRACER_COURSE_TESTS) + "/scenes")) {
        const std::string stem = entry.path().stem().string();
        if (entry.path().extension() == ".txt" && stem.rfind("test", 0) == 0)
            scan(entry.path().string(), "key" + stem.substr(4), all);
    }
    const std::set<Found>& found = all.found;
    std::set<Found> listed;
    for (const grade::AmbiguousPixel& p : grade::ambiguous_pixels()) {
        // The event the reason names: "... tangent to s1: ..." or "... meets s4 exactly ...".
        const std::string reason = p.reason;
        const std::size_t tangent = reason.find("tangent to "), meets = reason.find("meets ");
        const std::size_t at = tangent != std::string::npos ? tangent : meets;
        const std::size_t name = at + (tangent != std::string::npos ? 11 : 6);
        const std::size_t end = reason.find_first_of(": ", name);
        listed.insert({p.key, p.x, p.y, reason.substr(at, end - at)});
    }
    const auto named = [](const Found& f) {
        return std::get<0>(f) + " (" + std::to_string(std::get<1>(f)) + ", " +
               std::to_string(std::get<2>(f)) + ") " + std::get<3>(f);
    };
    for (const Found& f : found) expect(listed.count(f) == 1, __LINE__, named(f) + ": not in the table");
    for (const Found& f : listed)
        expect(found.count(f) == 1, __LINE__, named(f) + ": in the table, not found");
    // The exact tests decide: the prefilter leaves near misses too (17,014 candidates).
    CHECK(all.candidates > all.exact && all.exact == 52 && found.size() == 52);
}

TEST(the_exact_tests_find_a_known_rim_point_and_a_known_tangent_and_not_their_mirror_images) {
    SceneText text;
    text.view = {{"LEFT", "-1"}, {"RIGHT", "1"}, {"BOTTOM", "-1"}, {"TOP", "1"}, {"NEAR", "1"}};
    // Pixel (6, 2) of 8 x 8 has its corner at (0.5, 0.5, -1): (0.3 / 0.5)^2 + (0.4 / 0.5)^2 = 1.
    const NearPlanePoints rim(text, {"e", {"0.2", "0.1", "-1"}, {"0.5", "0.5", "0.7"}}, 8, 8);
    CHECK(rim.on_surface(6, 2));
    CHECK(!rim.on_surface(2, 2) && !rim.on_surface(6, 6) && !rim.on_surface(5, 2));
    // Radius 3 at distance 5: the ray through (0.75, 0, -1), pixel (7, 4)'s corner, is tangent.
    const exact::CornerRays rays("-1", "1", "-1", "1", "1", 8, 8);
    const exact::EllipsoidForm ball({"0", "0", "-5"}, {"3", "3", "3"});
    CHECK(ball.side(rays.exact(7, 4)) == 0);
    CHECK(ball.side(rays.exact(6, 4)) == 1 && ball.side(rays.exact(7, 3)) == -1);
}
