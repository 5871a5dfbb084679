// Ray/ellipsoid intersection: both roots, the near-plane cut, tangency, misses.
#include "check.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/shading.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/reference/unit_sphere_roots.h"

namespace {

using V = rt::Vec3<double>;

rt::Ellipsoid<double> ellipsoid(V centre, V scale) {
    rt::SphereSpec s;
    s.centre = centre;
    s.scale = scale;
    return rt::make_ellipsoid<double>(s);
}

// The reference's queries (brute_force.h) over the ellipsoid of this centre and scale.
rt::BruteForce<double> scene_with(V centre, V scale) {
    return rt::BruteForce<double>({ellipsoid(centre, scale)});
}

}  // namespace

TEST(entering_and_leaving_roots_of_a_unit_sphere) {
    const auto r = rt::intersect(ellipsoid({0, 0, -5}, {1, 1, 1}), V{}, V{0, 0, -1});
    CHECK(r.hit);
    CHECK_NEAR(r.near, 4.0, 1e-15);
    CHECK_NEAR(r.far, 6.0, 1e-15);
}

TEST(t_is_the_same_in_unit_and_world_space) {
    // The course's s1: scaled (2, 4, 2) at z = -10, met along -z at z = -8 and -12;
    // a direction of length 2 halves every t.
    const auto e = ellipsoid({0, 0, -10}, {2, 4, 2});
    const auto r = rt::intersect(e, V{}, V{0, 0, -2});
    CHECK(r.hit);
    CHECK_NEAR(r.near, 4.0, 1e-15);
    CHECK_NEAR(r.far, 6.0, 1e-15);
    const auto up = rt::intersect(e, V{0, -10, -10}, V{0, 1, 0});
    CHECK_NEAR(up.near, 6.0, 1e-14);
    CHECK_NEAR(up.far, 14.0, 1e-14);
}

TEST(a_ray_from_inside_has_one_root_behind_it) {
    const auto r = rt::intersect(ellipsoid({0, 0, 0}, {3, 1, 2}), V{}, V{1, 0, 0});
    CHECK(r.hit);
    CHECK_NEAR(r.near, -3.0, 1e-15);
    CHECK_NEAR(r.far, 3.0, 1e-15);
}

TEST(a_ray_that_passes_by_misses) {
    CHECK(!rt::intersect(ellipsoid({0, 2.001, -5}, {1, 1, 1}), V{}, V{0, 0, -1}).hit);
    CHECK(!rt::intersect(ellipsoid({0, 0, -5}, {1, 1, 1}), V{}, V{0, 1, 0}).hit);
}

TEST(an_exactly_tangent_ray_is_a_hit) {
    const auto r = rt::intersect(ellipsoid({0, 1, -5}, {1, 1, 1}), V{}, V{0, 0, -1});
    CHECK(r.hit);
    CHECK_NEAR(r.near, 5.0, 1e-12);
    CHECK_NEAR(r.far, 5.0, 1e-12);
    // testShadow's eye ray through pixel (400, 150) touches s1 = unit sphere at (3, 3, -8)
    // (SPEC section 4); in double its discriminant rounds a little below zero.
    const double x = -1.0 + 2.0 * 400 / 600, y = 1.0 - 2.0 * 150 / 600;
    const auto shadow = rt::intersect(ellipsoid({3, 3, -8}, {1, 1, 1}), V{}, V{x, y, -1});
    CHECK(shadow.hit);
    CHECK_NEAR(shadow.near, shadow.far, 1e-6);
}

TEST(negative_scales_give_the_same_ellipsoid) {
    const auto a = rt::intersect(ellipsoid({1, 2, -9}, {2, 3, 1}), V{}, V{0.1, 0.2, -1});
    const auto b = rt::intersect(ellipsoid({1, 2, -9}, {-2, 3, -1}), V{}, V{0.1, 0.2, -1});
    CHECK(a.hit && b.hit);
    CHECK_EQ(a.near, b.near);
    CHECK_EQ(a.far, b.far);
    // The hit at the point of the surface nearest the eye, (1, 2, -8): its normal faces
    // the eye, and away from it where the ray sees the inside.
    const rt::Ellipsoid<double> e = ellipsoid({1, 2, -9}, {-2, 3, -1});
    const V p{1, 2, -8};
    CHECK_EQ(rt::surface_point(V{}, p, 1.0, false, e.centre, e.scale_squared).normal.z, 1.0);
    CHECK_EQ(rt::surface_point(V{}, p, 1.0, true, e.centre, e.scale_squared).normal.z, -1.0);
}

TEST(normal_is_position_over_scale_squared) {
    const rt::Ellipsoid<double> e = ellipsoid({0, 0, 0}, {2, 1, 1});
    const V p{std::sqrt(2.0), std::sqrt(0.5), 0};
    const rt::SurfacePoint<double> s = rt::surface_point(V{}, p, 1.0, false, e.centre, e.scale_squared);
    // (sqrt2/4, sqrt(0.5), 0) normalised
    const double len = std::sqrt(2.0 / 16 + 0.5);
    CHECK_NEAR(s.normal.x, std::sqrt(2.0) / 4 / len, 1e-15);
    CHECK_NEAR(s.normal.y, std::sqrt(0.5) / len, 1e-15);
    CHECK_NEAR(s.scaled_length, len, 1e-15);
}

TEST(the_near_plane_cuts_ellipsoids_open) {
    // A sphere of radius 0.5 centred on the near plane: the eye ray meets it at t = 0.5
    // (in front of the near plane, cut away) and t = 1.5, its inner surface.
    const rt::BruteForce<double> tracer = scene_with({0, 0, -1}, {0.5, 0.5, 0.5});
    const auto hit = tracer.closest(V{}, V{0, 0, -1}, 1.0);
    CHECK(hit.found());
    CHECK_NEAR(hit.t, 1.5, 1e-15);
    CHECK(hit.inside);
    // Entirely between the eye and the near plane: not visible.
    const rt::BruteForce<double> before = scene_with({0, 0, -0.5}, {0.2, 0.2, 0.2});
    CHECK(!before.closest(V{}, V{0, 0, -1}, 1.0).found());
    // Behind the eye: not visible.
    const rt::BruteForce<double> behind = scene_with({0, 0, 5}, {1, 1, 1});
    CHECK(!behind.closest(V{}, V{0, 0, -1}, 1.0).found());
}

TEST(a_hit_exactly_on_the_near_plane_is_not_visible) {
    // keyIllum's rim pixels: s4 = (0,0,-1) scaled (0.25,0.25,0.5), pixel (240, 345)
    // of 600x600 meets it at exactly t = 1 (a 3-4-5 triangle) and t = 0.6.
    const rt::BruteForce<double> tracer = scene_with({0, 0, -1}, {0.25, 0.25, 0.5});
    const double x = -1.0 + 2.0 * 240 / 600, y = 1.0 - 2.0 * 345 / 600;
    CHECK(!tracer.closest(V{}, V{x, y, -1}, 1.0).found());
    // One pixel further in, the inner surface is visible.
    const double x2 = -1.0 + 2.0 * 241 / 600;
    CHECK(tracer.closest(V{}, V{x2, y, -1}, 1.0).found());
}

// kRootUlps (spec_rules.h): a root within 8 scene ulps (scene_epsilon(): double's in
// long double too) of a ray's bound is at it, where the point at t = 1 does not settle it
// (a computed root handed over as it is). 6 ulps off, a root is at the bound; 12, past it.
template <typename Real>
void roots_near_a_bound_are_at_it() {
    const Real ulp = rt::scene_epsilon<Real>();
    const Real beyond = rt::visible_beyond(Real(rt::kEyeRayMinT));
    Real t;
    bool inside;
    // From inside the near plane's cut (near root behind it), the far root at 1 + 6 ulps
    // is on the near plane: not visible; at 1 + 12 ulps it is.
    CHECK(!rt::visible_root(rt::Roots<Real>{1, Real(0.5), 1 + 6 * ulp}, beyond, t, inside));
    CHECK(rt::visible_root(rt::Roots<Real>{1, Real(0.5), 1 + 12 * ulp}, beyond, t, inside));
    CHECK(inside);
    // A shadow ray's roots at 0.001 and at the light, 6 ulps off: not between them.
    const Real start = Real(rt::kShadowRayMinT);
    CHECK(!rt::blocks_segment(rt::Roots<Real>{1, start * (1 + 6 * ulp), 2}));
    CHECK(rt::blocks_segment(rt::Roots<Real>{1, start * (1 + 12 * ulp), 2}));
    CHECK(!rt::blocks_segment(rt::Roots<Real>{1, -1, 1 - 6 * ulp}));
    CHECK(rt::blocks_segment(rt::Roots<Real>{1, -1, 1 - 12 * ulp}));
}

TEST(a_root_within_a_few_ulps_of_a_bound_is_at_it) {
    roots_near_a_bound_are_at_it<double>();
    roots_near_a_bound_are_at_it<long double>();
}

// A ray whose origin lies on the surface to within the rounding of c = o'.o' - 1 has its
// root there at t = 0 exactly (unit_sphere_roots.h), whatever the ray's length. Here the
// mapped direction is 1e-12 long, as from a floor of radius 1e12 or through a window
// 1e-9 wide, so c / q, 11 ulps over 1e-12, would be about 1e-3: past 0.0001, a hit.
template <typename Real>
void a_root_at_the_origin_is_zero() {
    const Real ulp = rt::scene_epsilon<Real>();
    const Real dx = Real(-0.8e-12), dy = Real(0.6e-12);  // into the sphere from (1, 0, 0)
    for (const Real c : {Real(0), 11 * ulp, -11 * ulp}) {
        const rt::Roots<Real> r = rt::unit_sphere_roots(Real(1), Real(0), Real(0), c, dx, dy, Real(0));
        CHECK(r.hit != 0);
        CHECK(r.near == 0);
        CHECK_NEAR(double(r.far / Real(1.6e12)), 1.0, 1e-12);  // the far side: -2 o'.d' / d'.d'
    }
    // Farther from the surface than c's rounding: the origin's own offset, as computed.
    const rt::Roots<Real> off = rt::unit_sphere_roots(Real(1), Real(0), Real(0), 100 * ulp, dx, dy, Real(0));
    CHECK(off.near > 0);
}

TEST(a_root_at_the_origin_is_zero_however_short_the_ray) {
    a_root_at_the_origin_is_zero<double>();
    a_root_at_the_origin_is_zero<long double>();
}

// The mirrored ray from a floor of radius 1e12 leaves it: the floor cannot be met again.
TEST(a_mirrored_ray_does_not_meet_its_own_surface_again) {
    const rt::BruteForce<double> tracer = scene_with({0, -1e12 - 1, -5}, {1e12, 1e12, 1e12});
    int own_hits = 0;
    for (int i = 1; i <= 50; ++i) {  // eye rays down onto the floor at several slants
        const V direction{0.01 * i, -0.1 - 0.005 * i, -1};
        const auto eye = tracer.closest(V{}, direction, 1.0);
        CHECK(eye.found());
        const V point = direction * eye.t;
        const V normal = rt::normalize(point - V{0, -1e12 - 1, -5});  // a sphere's
        const V mirrored = direction - normal * (2 * rt::dot(normal, direction));
        own_hits += tracer.closest(point, mirrored, rt::kReflectedRayMinT).found() ? 1 : 0;
    }
    CHECK_EQ(own_hits, 0);
}

TEST(the_nearest_of_several_is_taken) {
    const rt::BruteForce<double> tracer(
        {ellipsoid({0, 0, -10}, {1, 1, 1}), ellipsoid({0, 0, -5}, {1, 1, 1})});
    const auto hit = tracer.closest(V{}, V{0, 0, -1}, 1.0);
    CHECK_EQ(hit.ellipsoid, 1U);
    CHECK_NEAR(hit.t, 4.0, 1e-15);
    CHECK(!hit.inside);
}

TEST(shadow_rays_count_hits_strictly_between_point_and_light) {
    const rt::BruteForce<double> tracer = scene_with({0, 0, -5}, {1, 1, 1});
    auto in_shadow = [&](V point, V to_light) {
        std::uint32_t blocker = rt::kNoEllipsoid;
        return tracer.occluded(point, to_light, blocker);
    };
    CHECK(in_shadow(V{0, 0, -10}, V{0, 0, 10}));  // blocker in between
    CHECK(!in_shadow(V{0, 0, -10}, V{0, 0, 3}));  // light stops short of it
    CHECK(!in_shadow(V{0, 0, -2}, V{0, 0, 2}));   // blocker behind the point
    CHECK(in_shadow(V{0, 0, -6}, V{0, 0, 10}));   // the point's own shell blocks
    CHECK(!in_shadow(V{0, 0, -6}, V{0, 0, 1}));   // a light inside lights the inside
}
