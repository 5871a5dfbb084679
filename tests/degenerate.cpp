// The degenerate-but-legal test: every scene of tests/degenerate (a light on a surface,
// exponent 0 and 1e300, an ellipsoid around the camera, no spheres, 1x1, 40 spheres...)
// must render, and render the same every time. For each scene:
//   - every eye ray's colour is finite before clamping (no NaN or infinity that the
//     clamp would silently turn into black or white);
//   - two renders in this process are byte-identical;
//   - negating every scale gives the very same image (the ellipsoid is the same);
//   - raytracer.exe, run twice, exits 0 silently and writes that same image each time.
//
//   degenerate <raytracer.exe> <tests/degenerate folder>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "raytracer/image.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"
#include "raytracer/reference/brute_force.h"
#include "raytracer/reference/whitted.h"
#include "raytracer/render.h"
#include "run_program.h"

namespace fs = std::filesystem;

namespace {

int failures = 0;

void expect(bool ok, const std::string& name, const std::string& what) {
    if (ok) return;
    ++failures;
    std::cout << "FAIL  " << name << ": " << what << "\n";
}

// Pixels whose colour has a non-finite channel, traced by the reference (whitted.h),
// whose bytes every path gives.
long long non_finite_pixels(const rt::Scene& scene) {
    const rt::Whitted<double, rt::BruteForce<double>> reference(
        scene, rt::BruteForce<double>(rt::make_ellipsoids<double>(scene)));
    auto scratch = reference.make_scratch();
    long long count = 0;
    for (int r = 0; r < scene.rows; ++r) {
        const double y = scene.top - (scene.top - scene.bottom) * r / scene.rows;
        for (int c = 0; c < scene.columns; ++c) {
            const double x = scene.left + (scene.right - scene.left) * c / scene.columns;
            const rt::Vec3<double> colour = reference.eye_ray_colour({x, y, -scene.near_plane}, scratch);
            if (!std::isfinite(colour.x) || !std::isfinite(colour.y) || !std::isfinite(colour.z)) ++count;
        }
    }
    return count;
}

bool same(const rt::Image& a, const rt::Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb == b.rgb;
}

void check_scene(const fs::path& raytracer, const fs::path& scratch, const fs::path& file) {
    const std::string name = file.filename().u8string();
    const int failures_before = failures;
    const rt::Scene scene = rt::load_scene(file.string());

    const long long bad_pixels = non_finite_pixels(scene);
    expect(bad_pixels == 0, name, std::to_string(bad_pixels) + " pixels have a non-finite colour");

    const rt::Image image = rt::render<double>(scene);
    expect(image.width == scene.columns && image.height == scene.rows, name, "image of the wrong size");
    expect(same(image, rt::render<double>(scene)), name, "a second render differs");

    rt::Scene mirrored = scene;
    for (rt::SphereSpec& s : mirrored.spheres) s.scale = s.scale * -1.0;
    expect(same(image, rt::render<double>(mirrored)), name, "negated scales give another image");

    const fs::path box = scratch / name, work = box / "work";
    fs::create_directories(work);
    for (int run = 1; run <= 2; ++run) {
        const run_program::Result r = run_program::run(raytracer, {fs::absolute(file).string()}, work, box);
        const std::string which = "raytracer.exe run " + std::to_string(run);
        expect(r.status == 0, name, which + " exit status " + std::to_string(r.status) + ": " + r.err);
        expect(r.out.empty() && r.err.empty(), name, which + " printed: " + r.out + r.err);
        rt::Image written;
        std::string error;
        const fs::path output = work / fs::u8path(scene.output);
        expect(rt::read_ppm(output.string(), written, error), name,
               std::string(which).append(": ").append(error));
        expect(same(image, written), name, which + " wrote another image than rt::render");
        std::error_code ignored;
        fs::remove(output, ignored);
        expect(fs::is_empty(work), name, which + " left a stray file");
    }
    if (failures == failures_before) std::cout << "ok    " << name << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: degenerate <raytracer.exe> <tests/degenerate folder>\n";
        return 2;
    }
    const fs::path raytracer = fs::absolute(argv[1]);
    std::vector<fs::path> scenes;
    for (const fs::directory_entry& entry : fs::directory_iterator(argv[2]))
        if (entry.path().extension() == ".txt") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    expect(scenes.size() >= 20, "folder", std::to_string(scenes.size()) + " scenes, expected 20 or more");

    std::mt19937_64 random(std::random_device{}());
    const fs::path scratch = fs::temp_directory_path() / ("raytracer-degenerate-" + std::to_string(random()));
    for (const fs::path& file : scenes) {
        try {
            check_scene(raytracer, scratch, file);
        } catch (const std::exception& e) {
            expect(false, file.filename().u8string(), std::string("exception: ") + e.what());
        }
    }
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
    std::cout << scenes.size() << " scenes, " << failures << " failed checks\n";
    return failures == 0 ? 0 : 1;
}
