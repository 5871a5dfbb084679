// embree_tracer SCENE OUT.ppm [--threads N]: the yardstick of the scale table (d) (issue 14), a renderer on
// Intel's Embree 3. It renders a scene as raytracer.exe does, byte for byte, with the reference tracer
// (whitted.h) over a geometry whose queries Embree's BVH answers; built only where Embree 3 is installed.
//
// Embree knows the ellipsoids as one user geometry of axis-aligned boxes, in float, and only prunes: every
// ellipsoid whose box a ray meets is tried in double by the callbacks below, with the project's own
// intersect() and the rules of spec_rules.h, so the answers are those of brute_force.h. Two things keep
// float from culling a true hit:
// - each box is the ellipsoid's grown by 1e-3 of each scale (as bvh.h's) and by 16 float ulps of the
//   scene's extent R (ellipsoids and lights), rounded outward: a ray's origin and the points it reaches
//   lie within R of the origin per axis (the camera, surface points, lights), so the float ray strays at
//   most ~3 ulps of R from the double one, and Embree's own slab test rounds by a few more;
// - a ray's tfar is the float just above the nearest root found so far (ties go to the lower index), so
//   no box holding a root as near is skipped.
// Whole process time is what the benchmark counts: parse, Embree's build, render, write.
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/ellipsoid.h"
#include "raytracer/reference/spec_rules.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/scene_error.h"

namespace {

using V = rt::Vec3<double>;
using Ellipsoid = rt::Ellipsoid<double>;

// The smallest float above x.
float float_above(double x) {
    float f = static_cast<float>(x);
    if (static_cast<double>(f) <= x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}
float float_below(double x) { return -float_above(-x); }

// One query's state, reached from the callbacks through the context Embree passes on (the context
// comes first, as in Embree's tutorials): the double ray and what is found on it.
struct Query {
    RTCIntersectContext context;
    const Ellipsoid* all;
    V origin, direction;
    double beyond;  // visible_beyond(min_t) of a closest-hit query
    rt::NearestHit<double> best;
    std::uint32_t blocker;  // the ellipsoid that blocked a shadow ray
};

// The boxes, computed before the build; Embree asks for them during rtcCommitScene() only.
void box_of(const RTCBoundsFunctionArguments* args) {
    *args->bounds_o = static_cast<const RTCBounds*>(args->geometryUserPtr)[args->primID];
}

// Closest hit: ellipsoid primID as BruteForce::closest() tries it.
void intersect_one(const RTCIntersectFunctionNArguments* args) {
    if (args->valid[0] == 0) return;  // rtcIntersect1: one ray
    Query& q = *reinterpret_cast<Query*>(args->context);
    const std::uint32_t i = args->primID;
    double t;
    bool inside;
    if (rt::visible_root(rt::intersect(q.all[i], q.origin, q.direction), q.beyond, t, inside) &&
        q.best.replaced_by(t, i)) {
        q.best = {t, i, inside};
        RTCRayHit& ray_hit = *reinterpret_cast<RTCRayHit*>(args->rayhit);
        ray_hit.ray.tfar = float_above(t);  // boxes entered beyond it cannot hold an equal or nearer root
        ray_hit.hit.geomID = args->geomID, ray_hit.hit.primID = i;
    }
}

// Any hit: whether ellipsoid primID blocks the shadow ray's segment; -inf ends the traversal.
void occluded_one(const RTCOccludedFunctionNArguments* args) {
    if (args->valid[0] == 0) return;
    Query& q = *reinterpret_cast<Query*>(args->context);
    if (rt::blocks_segment(q.all[args->primID], q.origin, q.direction)) {
        q.blocker = args->primID;
        reinterpret_cast<RTCRay*>(args->ray)->tfar = -std::numeric_limits<float>::infinity();
    }
}

void report_error(void* /*unused*/, RTCError code, const char* message) {
    std::fprintf(stderr, "embree_tracer: Embree error %d: %s\n", static_cast<int>(code), message);
    std::exit(5);
}

// The geometry queries of brute_force.h, with Embree's BVH to prune. A scene beyond float's range (a
// coordinate over 1e15, or NEAR under 1e-30: Embree drops boxes beyond 1.8e18) is left to BruteForce.
class EmbreeGeometry {
public:
    EmbreeGeometry(const rt::Scene& scene, unsigned threads)
        : plain_(rt::make_ellipsoids<double>(scene)),
          count_(static_cast<std::uint32_t>(scene.spheres.size())) {
        // R: every ray's origin, and every point a ray reaches before its hit or light, lies within R of
        // the origin on each axis (the camera is at the origin).
        double extent = 0;
        for (std::uint32_t i = 0; i < count_; ++i) {
            const Ellipsoid& e = plain_.ellipsoid(i);
            const double s = std::max({std::abs(e.scale.x), std::abs(e.scale.y), std::abs(e.scale.z)});
            extent = std::max(
                {extent, std::abs(e.centre.x) + s, std::abs(e.centre.y) + s, std::abs(e.centre.z) + s});
        }
        for (const rt::LightSpec& l : scene.lights)
            extent =
                std::max({extent, std::abs(l.position.x), std::abs(l.position.y), std::abs(l.position.z)});
        const double window = std::max({std::abs(scene.left), std::abs(scene.right), std::abs(scene.bottom),
                                        std::abs(scene.top), scene.near_plane});
        if (count_ == 0 || !(extent <= 1e15 && window <= 1e15 && scene.near_plane >= 1e-30)) return;

        const std::string config = "threads=" + std::to_string(threads);
        device_.reset(rtcNewDevice(config.c_str()));
        if (!device_) report_error(nullptr, rtcGetDeviceError(nullptr), "rtcNewDevice failed");
        rtcSetDeviceErrorFunction(device_.get(), report_error, nullptr);
        const double slack = 16 * double(std::numeric_limits<float>::epsilon()) * extent;
        std::vector<RTCBounds> boxes(count_);
        for (std::uint32_t i = 0; i < count_; ++i) {
            const Ellipsoid& e = plain_.ellipsoid(i);
            const V grow = V{std::abs(e.scale.x), std::abs(e.scale.y), std::abs(e.scale.z)} * 1.001 +
                           V{slack, slack, slack};
            const V& c = e.centre;
            boxes[i] = {float_below(c.x - grow.x), float_below(c.y - grow.y), float_below(c.z - grow.z), 0,
                        float_above(c.x + grow.x), float_above(c.y + grow.y), float_above(c.z + grow.z), 0};
        }
        scene_.reset(rtcNewScene(device_.get()));
        rtcSetSceneBuildQuality(scene_.get(), kQuality);
        RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryBuildQuality(geometry, kQuality);
        rtcSetGeometryUserPrimitiveCount(geometry, count_);
        rtcSetGeometryUserData(geometry, boxes.data());  // the bounds function's geometryUserPtr
        rtcSetGeometryBoundsFunction(geometry, box_of, nullptr);
        rtcSetGeometryIntersectFunction(geometry, intersect_one);
        rtcSetGeometryOccludedFunction(geometry, occluded_one);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_.get(), geometry);
        rtcCommitScene(scene_.get());
        rtcSetGeometryUserData(geometry, nullptr);  // the boxes go; the callbacks use the Query
        rtcReleaseGeometry(geometry);               // the scene holds it
    }

    const Ellipsoid& ellipsoid(std::uint32_t i) const { return plain_.ellipsoid(i); }

    // As BruteForce::closest(): the nearest visible root beyond min_t, ties to the lower index.
    rt::NearestHit<double> closest(const V& origin, const V& direction, double min_t) const {
        if (!scene_) return plain_.closest(origin, direction, min_t);
        Query q = query(origin, direction);
        q.beyond = rt::visible_beyond(min_t);
        RTCRayHit ray_hit = {};
        set_ray(ray_hit.ray, origin, direction, std::numeric_limits<float>::infinity());
        ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_.get(), &q.context, &ray_hit);
        return q.best;
    }

    // As BruteForce::occluded(): the segment from point to point + to_light, trying first the
    // ellipsoid that blocked this light last.
    bool occluded(const V& point, const V& to_light, std::uint32_t& blocker) const {
        if (!scene_) return plain_.occluded(point, to_light, blocker);
        if (blocker < count_ && rt::blocks_segment(plain_.ellipsoid(blocker), point, to_light)) return true;
        Query q = query(point, to_light);
        RTCRay ray = {};
        set_ray(ray, point, to_light, float_above(1.0));
        rtcOccluded1(scene_.get(), &q.context, &ray);
        if (ray.tfar >= 0) return false;
        blocker = q.blocker;
        return true;
    }

private:
    // Embree's default. Measured here (2 cores, whole process, 9 runs of each scale scene): HIGH within 2%
    // of it everywhere, LOW 5-10% slower on the sphereflakes and 7% faster on random 100k (a cheaper build).
    static constexpr RTCBuildQuality kQuality = RTC_BUILD_QUALITY_MEDIUM;

    Query query(const V& origin, const V& direction) const {
        Query q{{}, &plain_.ellipsoid(0), origin, direction, 0, {}, rt::kNoEllipsoid};
        rtcInitIntersectContext(&q.context);
        return q;
    }
    // The float ray from tnear 0: min_t is decided in double by the callbacks.
    static void set_ray(RTCRay& ray, const V& origin, const V& direction, float tfar) {
        ray.org_x = float(origin.x), ray.org_y = float(origin.y), ray.org_z = float(origin.z);
        ray.dir_x = float(direction.x), ray.dir_y = float(direction.y), ray.dir_z = float(direction.z);
        ray.tnear = 0, ray.tfar = tfar, ray.mask = 0xFFFFFFFFU, ray.flags = 0, ray.time = 0;
    }

    struct ReleaseDevice {
        void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
    };
    struct ReleaseScene {
        void operator()(RTCScene s) const { rtcReleaseScene(s); }
    };
    rt::BruteForce<double> plain_;  // the ellipsoids, and the queries where Embree is not used
    std::uint32_t count_;
    std::unique_ptr<RTCDeviceTy, ReleaseDevice> device_;
    std::unique_ptr<RTCSceneTy, ReleaseScene> scene_;  // released before its device
};

int usage() {
    std::fprintf(stderr, "usage: embree_tracer SCENE OUT.ppm [--threads N]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> files;
    unsigned threads = std::max(1U, std::thread::hardware_concurrency());
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--threads" && i + 1 < argc) {
            const int n = std::atoi(argv[++i]);
            if (n < 1 || n > 1024) return usage();
            threads = static_cast<unsigned>(n);
        } else {
            files.push_back(a);
        }
    }
    if (files.size() != 2) return usage();
    try {
        const rt::Scene scene = rt::load_scene(files[0]);
        const rt::Whitted<double, EmbreeGeometry> tracer(scene, EmbreeGeometry(scene, threads));
        const std::size_t row_bytes = static_cast<std::size_t>(scene.columns) * 3;
        std::vector<std::uint8_t> pixels(row_bytes * static_cast<std::size_t>(scene.rows));
        // Bands of 4 rows from a shared counter, as raytracer.exe takes them.
        constexpr int kBandRows = 4;
        std::atomic<int> next_row{0};
        auto take_rows = [&] {
            auto scratch = tracer.make_scratch();
            for (int r = next_row.fetch_add(kBandRows); r < scene.rows; r = next_row.fetch_add(kBandRows))
                for (int row = r; row < std::min(r + kBandRows, scene.rows); ++row) {
                    std::uint8_t* const out = pixels.data() + static_cast<std::size_t>(row) * row_bytes;
                    for (int c = 0; c < scene.columns; ++c)
                        tracer.pixel(c, row, out + rt::bytes_of_pixels(c), scratch);
                }
        };
        std::vector<std::thread> helpers;
        for (unsigned t = 1; t < std::min<unsigned>(threads, static_cast<unsigned>(scene.rows)); ++t)
            helpers.emplace_back(take_rows);
        take_rows();
        for (std::thread& t : helpers) t.join();
        const std::string error =
            rt::save_imageP6(scene.columns, scene.rows, files[1].c_str(), pixels.data());
        if (!error.empty()) {
            std::fprintf(stderr, "embree_tracer: %s\n", error.c_str());
            return 3;
        }
    } catch (const rt::SceneError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "embree_tracer: %s\n", e.what());
        return 5;
    }
    return 0;
}
