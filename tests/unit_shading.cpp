// Each term of the illumination model (SPEC section 5) against hand-computed values,
// and the conversion of a colour to bytes (section 6).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <random>

#include "check.h"
#include "raytracer/finish_lanes.h"
#include "raytracer/image.h"
#include "raytracer/lanes.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/power.h"
#include "raytracer/reference/shading.h"
#include "raytracer/reference/whitted.h"

namespace {

using V = rt::Vec3<double>;

rt::SphereSpec sphere(V centre, double radius, V colour, double ka, double kd, double ks, double kr,
                      double n) {
    rt::SphereSpec s;
    s.centre = centre;
    s.scale = {radius, radius, radius};
    s.colour = colour;
    s.ka = ka;
    s.kd = kd;
    s.ks = ks;
    s.kr = kr;
    s.shininess = n;
    return s;
}

rt::Scene scene(V ambient, V background = {0.25, 0.5, 0.75}) {
    rt::Scene s;
    s.ambient = ambient;
    s.background = background;
    return s;
}

void light(rt::Scene& s, V position, V intensity) { s.lights.push_back({position, intensity, 0}); }

// The reference's colour along an eye ray (whitted.h: what every path's bytes are held to).
V trace(const rt::Scene& s, V direction) {
    const rt::Whitted<double, rt::BruteForce<double>> reference(
        s, rt::BruteForce<double>(rt::make_ellipsoids<double>(s)));
    auto scratch = reference.make_scratch();
    return reference.eye_ray_colour(direction, scratch);
}

}  // namespace

TEST(eye_rays_that_miss_return_the_background) {
    const V c = trace(scene({1, 1, 1}), {0, 0, -1});
    CHECK_EQ(c.x, 0.25);
    CHECK_EQ(c.y, 0.5);
    CHECK_EQ(c.z, 0.75);
}

TEST(ambient_is_ka_times_ia_times_colour) {
    rt::Scene s = scene({0.75, 0.5, 1});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {0.5, 1, 0.25}, 0.8, 0, 0, 0, 1));
    const V c = trace(s, {0, 0, -1});
    CHECK_NEAR(c.x, 0.8 * 0.75 * 0.5, 1e-15);
    CHECK_NEAR(c.y, 0.8 * 0.5 * 1, 1e-15);
    CHECK_NEAR(c.z, 0.8 * 1 * 0.25, 1e-15);
}

TEST(diffuse_follows_the_cosine_to_the_light) {
    rt::Scene s = scene({0, 0, 0});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {0.5, 1, 0.25}, 0, 0.9, 0, 0, 1));
    light(s, {0, 0, 0}, {1, 0.5, 1});
    V c = trace(s, {0, 0, -1});  // hits (0,0,-4) facing the light: N.L = 1
    CHECK_NEAR(c.x, 0.9 * 1 * 0.5, 1e-15);
    CHECK_NEAR(c.y, 0.9 * 0.5 * 1, 1e-15);
    // A light 60 degrees off the normal at (0,0,-4): N.L = cos 60 = 0.5.
    s.lights[0].position = {std::sqrt(3.0), 0, -3};
    c = trace(s, {0, 0, -1});
    CHECK_NEAR(c.x, 0.9 * 1 * 0.5 * 0.5, 1e-12);
    // A light behind the surface gives nothing (and no specular either).
    s.lights[0].position = {0, 0, -20};
    s.spheres[0].ks = 1;
    c = trace(s, {0, 0, -1});
    CHECK_EQ(c.x, 0.0);
}

TEST(specular_is_not_tinted_by_the_object_colour) {
    rt::Scene s = scene({0, 0, 0});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {1, 0, 0}, 0, 0, 0.5, 0, 10));
    light(s, {0, 0, 0}, {1, 1, 1});
    const V c = trace(s, {0, 0, -1});  // R = V: (R.V)^n = 1
    CHECK_NEAR(c.x, 0.5, 1e-15);
    CHECK_NEAR(c.y, 0.5, 1e-15);
}

TEST(specular_falls_off_as_r_dot_v_to_the_n) {
    // Light at 60 degrees from the normal, viewer along the normal: R.V = cos 60 = 0.5.
    rt::Scene s = scene({0, 0, 0});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {1, 1, 1}, 0, 0, 1, 0, 3));
    light(s, {std::sqrt(3.0), 0, -3}, {1, 1, 1});
    const V c = trace(s, {0, 0, -1});
    CHECK_NEAR(c.y, 0.125, 1e-12);
}

TEST(a_blocked_light_leaves_only_ambient) {
    rt::Scene s = scene({0.5, 0.5, 0.5});
    s.spheres.push_back(sphere({0, 0, -10}, 1, {1, 1, 1}, 1, 1, 1, 0, 1));
    s.spheres.push_back(sphere({0, 5, -9}, 0.5, {1, 1, 1}, 1, 1, 1, 0, 1));  // between point and light
    light(s, {0, 10, -8}, {1, 1, 1});
    const V c = trace(s, {0, 0.05, -1});
    CHECK_NEAR(c.x, 0.5, 1e-15);
}

TEST(reflections_add_kr_times_what_the_mirror_sees) {
    // A mirror in front, a sphere behind the eye that only the mirror shows.
    rt::Scene s = scene({0.5, 0.5, 0.5});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {0, 0, 0}, 0, 0, 0, 0.5, 1));
    s.spheres.push_back(sphere({0, 0, 5}, 1, {1, 0.5, 0}, 1, 0, 0, 0, 1));
    const V c = trace(s, {0, 0, -1});
    CHECK_NEAR(c.x, 0.5 * 0.5 * 1, 1e-15);
    CHECK_NEAR(c.y, 0.5 * 0.5 * 0.5, 1e-15);
}

TEST(reflected_rays_that_miss_return_black) {
    rt::Scene s = scene({0, 0, 0}, {1, 1, 1});
    s.spheres.push_back(sphere({0, 0, -5}, 1, {0, 0, 0}, 0, 0, 0, 1, 1));
    const V c = trace(s, {0, 0, -1});
    CHECK_EQ(c.x, 0.0);
}

TEST(at_most_three_reflection_rays_per_pixel) {
    // The eye inside a mirror sphere: every bounce hits the shell again and adds its
    // ambient term a, weighted by 0.5 per bounce: a (1 + 1/2 + 1/4 + 1/8), no 1/16.
    rt::Scene s = scene({0.4, 0.4, 0.4});
    s.spheres.push_back(sphere({0, 0, 0}, 10, {1, 1, 1}, 1, 0, 0, 0.5, 1));
    const V c = trace(s, {0, 0, -1});
    CHECK_NEAR(c.x, 0.4 * 1.875, 1e-15);
}

TEST(a_light_inside_an_ellipsoid_lights_only_its_inside) {
    // testIllum: a light at the centre of a sphere that the near plane cuts open.
    rt::Scene s = scene({0, 0, 0});
    s.spheres.push_back(sphere({0, 0, -1}, 0.5, {1, 1, 1}, 0, 1, 0, 0, 1));
    s.spheres.push_back(sphere({0, 0, -10}, 5, {1, 1, 1}, 0, 1, 0, 0, 1));
    light(s, {0, 0, -1}, {1, 1, 1});
    CHECK_NEAR(trace(s, {0, 0, -1}).x, 1.0, 1e-12);    // the inner surface, facing the light
    CHECK_EQ(trace(s, {0.05, 0.05, -1}).x > 0, true);  // still inside the cut-open shell
    CHECK_EQ(trace(s, {0.55, 0, -1}).x, 0.0);          // the big sphere: the shell shades it
    s.spheres.erase(s.spheres.begin());
    CHECK(trace(s, {0.55, 0, -1}).x > 0);  // without the shell it is lit
}

TEST(colours_are_clamped_then_truncated) {
    CHECK_EQ(int{rt::to_byte(0.25)}, 63);
    CHECK_EQ(int{rt::to_byte(0.5)}, 127);
    CHECK_EQ(int{rt::to_byte(0.375)}, 95);
    CHECK_EQ(int{rt::to_byte(1.0)}, 255);
    CHECK_EQ(int{rt::to_byte(7.5)}, 255);
    CHECK_EQ(int{rt::to_byte(-0.1)}, 0);
    CHECK_EQ(int{rt::to_byte(std::numeric_limits<double>::quiet_NaN())}, 0);
    CHECK_EQ(int{rt::to_byte(0.999F)}, 254);
    // A level a few ulps of the scene's decimals below a step is that step: the scene's
    // 0.6 means 153 (0.6 * 255), whichever precision the product is taken in.
    CHECK_EQ(int{rt::to_byte(0.6)}, 153);
    CHECK_EQ(int{rt::to_byte(static_cast<long double>(0.6))}, 153);
    CHECK_EQ(int{rt::to_byte(0.6 - 1e-6)}, 152);
}

// (R.V)^n by multiplications for whole n (power.h): exact where the power is
// representable, within n ulps elsewhere, std::pow for any other n.
TEST(whole_exponents_are_recognised_and_others_go_to_pow) {
    CHECK_EQ(rt::whole_exponent(50.0), 50);
    CHECK_EQ(rt::whole_exponent(0.0), 0);
    CHECK_EQ(rt::whole_exponent(65536.0), 65536);
    CHECK_EQ(rt::whole_exponent(65537.0), -1);
    CHECK_EQ(rt::whole_exponent(50.5), -1);
    CHECK_EQ(rt::whole_exponent(-2.0), -1);
    CHECK_EQ(rt::whole_exponent(std::numeric_limits<double>::quiet_NaN()), -1);
    CHECK_EQ(rt::whole_exponent(std::numeric_limits<double>::infinity()), -1);
    CHECK_EQ(rt::specular_power(0.25, 0.5, rt::whole_exponent(0.5)), 0.5);
}

TEST(whole_powers_are_exact_where_representable) {
    CHECK_EQ(rt::whole_power(0.5, 3), 0.125);
    CHECK_EQ(rt::whole_power(0.75, 2), 0.5625);
    CHECK_EQ(rt::whole_power(1.0, 1000), 1.0);
    CHECK_EQ(rt::whole_power(0.3, 0), 1.0);
    CHECK_EQ(rt::whole_power(0.3, 1), 0.3);
    CHECK_EQ(rt::whole_power(0.5, 1074), std::ldexp(1.0, -1074));  // the smallest subnormal
}

TEST(whole_powers_are_within_n_ulps_of_the_exact_power) {
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> base(0.05, 1.0);
    const std::int32_t exponents[] = {2, 3, 7, 10, 20, 50, 100, 200, 1000};
    double worst = 0;  // in units of n ulps
    for (const std::int32_t n : exponents)
        for (int i = 0; i < 2000; ++i) {
            const double x = base(random);
            const long double exact = std::pow(static_cast<long double>(x), static_cast<long double>(n));
            if (exact < 1e-300L) continue;  // subnormal results have fewer digits
            const double got = rt::whole_power(x, n);
            const long double ulps =
                std::fabs(static_cast<long double>(got) - exact) /
                (exact * static_cast<long double>(std::numeric_limits<double>::epsilon()));
            worst = std::max(worst, static_cast<double>(ulps) / n);
        }
    CHECK(worst <= 1.0);
    CHECK(worst > 0);  // not vacuous: some powers do carry rounding
}

// A tile's Finish knows the exponent its lanes share only after share_exponent(), and
// only where every lane has it (set_lane() forgets it); add_light() gives each lane the
// same bits whether it runs one loop for the shared exponent or a mask per lane.
TEST(a_shared_exponent_is_known_only_where_every_lane_has_it) {
    using Q = rt::Lanes<double, 4>;
    auto finish = [](std::initializer_list<double> shininess) {
        rt::Finish<Q> f{};
        int k = 0;
        for (double n : shininess) {
            const rt::SphereSpec s = sphere({0, 0, -5}, 1, {0.5, 0.6, 0.7}, 0.1, 0.5, 0.8, 0, n);
            rt::set_lane(f, k++, rt::finish_of(rt::make_ellipsoid<double>(s)));
        }
        return f;
    };
    rt::Finish<Q> same = finish({20, 20, 20, 20}), mixed = finish({20, 20, 50, 20}),
                  fractional = finish({2.5, 2.5, 2.5, 2.5});
    CHECK_EQ(same.shared_exponent, -1);  // not yet found
    rt::share_exponent(same), rt::share_exponent(mixed), rt::share_exponent(fractional);
    CHECK_EQ(same.shared_exponent, 20);
    CHECK_EQ(mixed.shared_exponent, -1);
    CHECK_EQ(fractional.shared_exponent, -1);
    // Lanes of one surface point and light: R.V = 0.8 in each (R = (0.6, 0, 0.8)).
    rt::SurfacePoint<Q> s;
    s.normal = rt::Vec3<Q>::from(V{0, 0, 1}), s.to_viewer = rt::Vec3<Q>::from(V{0, 0, 1});
    rt::LightRay<Q> r;
    r.l = rt::Vec3<Q>::from(V{-0.6, 0, 0.8}), r.n_dot_l = Q(0.8);
    const rt::Vec3<Q> intensity = rt::Vec3<Q>::from(V{1, 1, 1});
    rt::Finish<Q> unshared = same;
    unshared.shared_exponent = -1;
    rt::Vec3<Q> a = rt::Vec3<Q>::from(V{0, 0, 0}), b = a;
    rt::add_light(a, s, r, intensity, same, rt::LaneBits(0xF));
    rt::add_light(b, s, r, intensity, unshared, rt::LaneBits(0xF));
    for (int k = 0; k < 4; ++k) CHECK(a.x[k] == b.x[k] && a.y[k] == b.y[k] && a.z[k] == b.z[k]);
    CHECK(a.x[0] > 0.5 * 0.5 * 0.8);  // the specular term was added
}
