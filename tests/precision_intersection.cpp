// The intersection's error behaviour (include/raytracer/reference/ellipsoid.h) in each precision:
// tangency, far and thin ellipsoids, roots without cancellation, inside or outside.
#include <cfloat>
#include <cmath>

#include "check.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"

namespace {

template <typename Real>
rt::Ellipsoid<Real> ellipsoid(rt::Vec3<double> centre, rt::Vec3<double> scale) {
    rt::SphereSpec s;
    s.centre = centre;
    s.scale = scale;
    return rt::make_ellipsoid<Real>(s);
}

template <typename Real>
rt::Roots<Real> eye_ray(const rt::Ellipsoid<Real>& e, double x, double y, double z) {
    return rt::intersect(e, rt::Vec3<Real>{}, rt::Vec3<Real>{Real(x), Real(y), Real(z)});
}

// The textbook discriminant b^2 - ac, for contrast.
double naive_unit_discriminant(const rt::Ellipsoid<double>& e, const rt::Vec3<double>& d_world) {
    const rt::Vec3<double> o = (rt::Vec3<double>{} - e.centre) / e.scale;
    const rt::Vec3<double> d = d_world / e.scale;
    const double a = dot(d, d), b = dot(o, d), c = dot(o, o) - 1;
    return (b * b - a * c) / (a * a);
}

}  // namespace

TEST(the_tolerance_is_the_scenes_precision_or_coarser) {
    CHECK_EQ(rt::scene_epsilon<float>(), FLT_EPSILON);
    CHECK_EQ(rt::scene_epsilon<double>(), DBL_EPSILON);
    CHECK_EQ(rt::scene_epsilon<long double>(), static_cast<long double>(DBL_EPSILON));
}

// Radius 3 at distance 5: the ray through (0.75, 0, -1) is exactly tangent (3-4-5).
TEST(an_exactly_tangent_ray_is_a_hit_in_every_precision) {
    CHECK(eye_ray(ellipsoid<float>({0, 0, -5}, {3, 3, 3}), 0.75, 0, -1).hit);
    CHECK(eye_ray(ellipsoid<double>({0, 0, -5}, {3, 3, 3}), 0.75, 0, -1).hit);
    CHECK(eye_ray(ellipsoid<long double>({0, 0, -5}, {3, 3, 3}), 0.75, 0, -1).hit);
    // The same tangency a million times farther and non-uniformly scaled.
    CHECK(eye_ray(ellipsoid<double>({0, 0, -5e6}, {3e6, 1, 3e6}), 0.75, 0, -1).hit);
    CHECK(eye_ray(ellipsoid<long double>({0, 0, -5e6}, {3e6, 1, 3e6}), 0.75, 0, -1).hit);
}

// A ray tangent in decimal but not in binary: the ellipsoid (0.8, 0.6, 0.5) at z = -1.3
// and the ray through (0, 0.5, -1) meet where 4.69 t^2 - 10.4 t + 5.76 has discriminant
// 108.16 - 108.16 = 0 (scenes/hard/light_inside_cut.txt). Rounded to double, long double
// finds it about half a double ulp below zero; with the scene's tolerance it agrees
// with double that the ray touches.
TEST(a_decimal_tangent_ray_is_a_hit_in_double_and_long_double) {
    const rt::Vec3<double> centre{0, 0, -1.3}, scale{0.8, 0.6, 0.5};
    const auto d = eye_ray(ellipsoid<double>(centre, scale), 0, 0.5, -1);
    const auto ld = eye_ray(ellipsoid<long double>(centre, scale), 0, 0.5, -1);
    CHECK(d.hit);
    CHECK(ld.hit);
    CHECK_NEAR(d.near, 10.4 / (2 * (0.5 * 0.5 / 0.36 + 4)), 1e-6);  // the double root -b/a
    CHECK_NEAR(ld.near, d.near, 1e-6);
}

TEST(a_ray_that_misses_by_a_millionth_is_a_miss) {
    CHECK(!eye_ray(ellipsoid<float>({0, 0, -5}, {3, 3, 3}), 0.75 * (1 + 1e-5), 0, -1).hit);
    CHECK(!eye_ray(ellipsoid<double>({0, 0, -5}, {3, 3, 3}), 0.75 * (1 + 1e-6), 0, -1).hit);
    CHECK(!eye_ray(ellipsoid<long double>({0, 0, -5}, {3, 3, 3}), 0.75 * (1 + 1e-6), 0, -1).hit);
}

// A unit sphere 1e9 away, hit half a radius off centre: b^2 and ac are ~1e18, so their
// rounding errors (~100) swamp their difference (0.75); the cross-product form
// (unit_sphere_roots.h) keeps 1 - |l|^2 = 0.75 to ~1e-7.
TEST(a_far_sphere_keeps_its_discriminant_in_double) {
    const auto e = ellipsoid<double>({0, 0, -1e9}, {1, 1, 1});
    const rt::Vec3<double> d{0.5e-9, 0, -1};
    const auto r = rt::intersect(e, rt::Vec3<double>{}, d);
    CHECK(r.hit);
    // Entry at z = -1e9 + sqrt(0.75): t = 1e9 - sqrt(0.75) since d.z = -1.
    CHECK_NEAR(r.near, 1e9 - std::sqrt(0.75), 1e-5);
    CHECK_NEAR(r.far, 1e9 + std::sqrt(0.75), 1e-5);
    // The textbook formula is off by far more than the answer is big.
    const double naive = naive_unit_discriminant(e, d);
    CHECK(std::fabs(naive * dot(d, d) - 0.75) > 0.01);
}

// A disc 1e-9 thick seen 0.004 rad from edge-on: double and long double agree on where.
TEST(a_thin_disc_edge_on_has_the_same_roots_in_double_and_long_double) {
    const rt::Vec3<double> centre{0, -0.02, -5}, scale{2, 1e-9, 2};
    const auto d = eye_ray(ellipsoid<double>(centre, scale), 0.1, -0.004, -1);
    const auto ld = eye_ray(ellipsoid<long double>(centre, scale), 0.1, -0.004, -1);
    CHECK(d.hit);
    CHECK(ld.hit);
    CHECK_NEAR(d.near, 5.0, 1e-6);  // the plane y = -0.02 at y = -0.004 t
    CHECK_NEAR(d.near / static_cast<double>(ld.near), 1.0, 1e-14);
    CHECK_NEAR(d.far / static_cast<double>(ld.far), 1.0, 1e-14);
}

// A ray leaving a surface point: the root at the origin must come out near zero (below
// the 0.0001 threshold), not as a cancelled -b + sqrt(...) of either sign.
TEST(the_root_at_a_rays_origin_is_near_zero) {
    const auto e = ellipsoid<double>({0, 0, 0}, {1e5, 1e5, 1e5});
    const rt::Vec3<double> on_surface{0, 1e5, 0};
    const auto r = rt::intersect(e, on_surface, rt::Vec3<double>{1, -1, 0});  // into the sphere
    CHECK(r.hit);
    CHECK(std::fabs(r.near) < 1e-9);
    CHECK_NEAR(r.far, 1e5, 1e-6);  // the chord at 45 degrees: t = R
}

// Entering or leaving is decided by which root was taken: from inside, the far one.
TEST(a_ray_from_inside_sees_the_inner_surface) {
    const rt::BruteForce<double> tracer({ellipsoid<double>({0, 0, 0}, {6, 4, 9})});
    const auto hit = tracer.closest({0, 0, 0}, {0, 0, -1}, 1.0);
    CHECK(hit.found());
    CHECK(hit.inside);
    CHECK_NEAR(hit.t, 9.0, 1e-12);
    const auto outside = tracer.closest({0, 0, 20}, {0, 0, -1}, 1.0);
    CHECK(!outside.inside);
    CHECK_NEAR(outside.t, 11.0, 1e-12);
}

// A light exactly on a surface: the shadow ray's root at the light is t = 1, which
// rounding used to put either side of 1 (SPEC section 5: blocked by 0.001 < t < 1 only).
// Ball (1.5, 1, 1.25) at z = -6, light at its rightmost point (1.5, 0, -6).
template <typename Real>
void check_light_on_surface() {
    const auto ball = ellipsoid<Real>({0, 0, -6}, {1.5, 1, 1.25});
    const rt::Vec3<Real> light{Real(1.5), 0, -6};
    // From outside, entering the ball at the light (the other root beyond it).
    for (const rt::Vec3<Real>& point : {rt::Vec3<Real>{4, 0, -6}, rt::Vec3<Real>{3, Real(1.1), -6},
                                        rt::Vec3<Real>{Real(1.6), Real(-2.3), -5}})
        CHECK(!rt::blocks_segment(ball, point, light - point));
    // From the ball's own bottom, along a chord that ends at the light: roots 0 and 1.
    const rt::Vec3<Real> bottom{0, -1, -6};
    CHECK(!rt::blocks_segment(ball, bottom, light - bottom));
    const rt::Roots<Real> chord = rt::intersect(ball, bottom, light - bottom);
    CHECK(chord.hit);
    CHECK_EQ(chord.far, Real(1));
    // A light 256 scene ulps inside the surface is behind it: the point test is that tight.
    const rt::Vec3<Real> inside{Real(1.5) * (1 - 256 * rt::scene_epsilon<Real>()), 0, -6}, outside{4, 0, -6};
    CHECK(rt::blocks_segment(ball, outside, inside - outside));
}

TEST(a_light_on_a_surface_is_not_blocked_by_it_in_any_precision) {
    check_light_on_surface<float>();
    check_light_on_surface<double>();
    check_light_on_surface<long double>();
}

// An eye ray whose pixel lies on the surface (scenes/hollow.txt, pixel (200, 72)): the
// shell (1.1, 0.8, 1) at z = -1.6 and the ray through (0, 0.64, -1) meet at t = 1 exactly
// (mapped: (0, 0.8, 0.6)), at a slant that amplifies the root's rounding; the point test
// makes the root exactly 1 in every precision, so the near plane cuts it away alike.
TEST(a_pixel_on_the_surface_gives_a_root_of_exactly_one) {
    CHECK_EQ(eye_ray(ellipsoid<float>({0, 0, -1.6}, {1.1, 0.8, 1}), 0, 0.64, -1).far, 1.0F);
    CHECK_EQ(eye_ray(ellipsoid<double>({0, 0, -1.6}, {1.1, 0.8, 1}), 0, 0.64, -1).far, 1.0);
    CHECK_EQ(eye_ray(ellipsoid<long double>({0, 0, -1.6}, {1.1, 0.8, 1}), 0, 0.64, -1).far, 1.0L);
    // A pixel a millionth off the surface keeps its computed root.
    CHECK(eye_ray(ellipsoid<double>({0, 0, -1.6}, {1.1, 0.8, 1}), 0, 0.64 + 1e-6, -1).far != 1.0);
}
