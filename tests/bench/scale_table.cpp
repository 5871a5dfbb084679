#include "scale_table.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench_process.h"
#include "image_diff.h"
#include "raytracer/image.h"
#include "raytracer/ppm.h"

namespace fs = std::filesystem;

namespace {

struct ScaleScene {
    std::string name, kind;  // kind and size as make_scene takes them
    int size;
    double embree_ms;  // issue 14's measurement of a renderer on Embree 3 (2 threads), where not run
};

// Ellipsoids in a scene of make_scene's: a flake of level L has 1 + 9 + ... + 9^L
// spheres and the floor.
long ellipsoids(const ScaleScene& s) {
    if (s.kind == "random") return s.size;
    long count = 1, level = 1;
    for (int l = 0; l < s.size; ++l) level *= 9, count += level;
    return count + 1;
}

// The scene written by make_scene, a program of its own, so that this process stays
// small: a child's peak memory as wait4() reports it includes its parent's at the time
// of the spawn (the memory the child starts with, before exec).
std::string write_scene(const fs::path& make_scene, const ScaleScene& s, int columns, int rows,
                        bool& failed) {
    std::string file = s.name + (columns == 400 && rows == 400 ? "" : "-small") + ".txt";
    if (bench::run({make_scene.string(), s.kind, std::to_string(s.size), file, std::to_string(columns),
                    std::to_string(rows)}) < 0) {
        std::fprintf(stderr, "benchmark: make_scene could not write %s\n", file.c_str());
        failed = true;
    }
    return file;
}

// Whether POV-Ray can run here: the script exists and `povray` answers.
bool have_povray(const fs::path& script) {
    if (script.empty() || !fs::exists(script)) return false;
    return bench::run({"/bin/sh", "-c", "command -v povray"}) >= 0;
}

// Whether two P6 files hold the same pixels; what differs, for the table's note.
std::string image_difference(const std::string& a, const std::string& b) {
    rt::Image x, y;
    std::string error;
    if (!rt::read_ppm(a, x, error) || !rt::read_ppm(b, y, error)) return "cannot compare: " + error;
    const ImageDiff d = compare_images(x, y);
    if (!d.same_size) return "sizes differ";
    if (d.differing_pixels == 0) return "";
    return std::to_string(d.differing_pixels) + " pixels differ, by up to " +
           std::to_string(d.largest_difference) + " levels";
}

}  // namespace

void scale_table(const fs::path& raytracer, const fs::path& make_scene, const fs::path& povray,
                 const fs::path& embree, bool quick, bool& failed) {
    auto timed = [&](const std::vector<std::string>& argv) {
        const bench::Run r = bench::run_measured(argv);
        if (r.seconds < 0) {
            std::fprintf(stderr, "benchmark: '%s' failed\n", argv.back().c_str());
            failed = true;
        }
        return r;
    };
    const std::vector<ScaleScene> scenes{
        {"flake3", "flake", 3, 50},          {"flake4", "flake", 4, 60},
        {"flake5", "flake", 5, 147},         {"random1k", "random", 1000, 51},
        {"random10k", "random", 10000, 120}, {"random100k", "random", 100000, 377}};
    const bool pov = !quick && have_povray(povray);
    const int runs = quick ? 1 : 5, pov_runs = 3;
    // embree_tracer, where given and it runs (tried on the first scene at 1x1): timed as raytracer.exe.
    bool embree_runs = !embree.empty();
    if (embree_runs) {
        const std::string probe = write_scene(make_scene, scenes.front(), 1, 1, failed);
        embree_runs = bench::run({embree.string(), probe, scenes.front().name + "-embree.ppm"}) >= 0;
        if (!embree_runs) std::printf("\n(embree_tracer does not run: %s)\n", embree.string().c_str());
    }
    int embree_same = 0;
    std::string embree_notes;
    std::printf(
        "\n(d) scale scenes at 400x400, whole process, all cores (target: >= 20x POV-Ray 3.7 on 2 threads, "
        "and no slower than Embree 3)\n");
    std::printf("  %-12s %11s %8s %8s %8s %9s %12s %7s %10s%s\n", "scene", "ellipsoids", "min", "median",
                "max", "Mrays/s", "POV-Ray", "ratio", embree_runs ? "Embree 3" : "Embree 3*",
                embree_runs ? "   ratio" : "");
    double random_1k = 0, random_100k = 0;
    for (const ScaleScene& s : scenes) {
        const std::string file = write_scene(make_scene, s, 400, 400, failed);
        bench::Stats ours, theirs, embree_stats;
        for (int r = 0; r < (pov ? pov_runs : 0); ++r)
            theirs.samples.push_back(timed({povray.string(), file, s.name + "-pov.ppm", "+WT2"}).seconds);
        const std::vector<std::string> embree_run{embree.string(), file, s.name + "-embree.ppm"};
        // Alternating, so that load on the machine falls on both alike.
        for (int r = 0; r < runs; ++r) {
            ours.samples.push_back(timed({raytracer.string(), file}).seconds);
            if (embree_runs) embree_stats.samples.push_back(timed(embree_run).seconds);
        }
        const double median = ours.median();
        std::printf("  %-12s %11ld %8.1f %8.1f %8.1f %9.2f", s.name.c_str(), ellipsoids(s), ours.min() * 1e3,
                    median * 1e3, ours.max() * 1e3, 400.0 * 400.0 / median / 1e6);
        if (pov)
            std::printf(" %9.1f ms %6.1fx", theirs.median() * 1e3, theirs.median() / median);
        else
            std::printf(" %12s %7s", "-", "-");
        if (embree_runs) {
            std::printf(" %7.1f ms %6.2fx\n", embree_stats.median() * 1e3, embree_stats.median() / median);
            const std::string difference = image_difference(s.name + ".ppm", s.name + "-embree.ppm");
            if (difference.empty())
                ++embree_same;
            else
                embree_notes += "  " + s.name + ": " + difference + "\n";
        } else {
            std::printf(" %7.0f ms\n", s.embree_ms);
        }
        if (s.name == "random1k") random_1k = median;
        if (s.name == "random100k") random_100k = median;
    }
    if (!pov) std::printf("  POV-Ray: %s\n", quick ? "not run in the quick table" : "not on this machine");
    if (embree_runs) {
        std::printf(
            "  Embree 3: embree_tracer (reference tracer on Embree's BVH), %d runs alternating with ours;\n"
            "  ratio: its median / ours (> 1: ours faster); images identical to ours on %d of %zu scenes\n%s",
            runs, embree_same, scenes.size(), embree_notes.c_str());
    } else {
        std::printf("  * issue 14's measurement on this machine kind, not of this run\n");
    }
    std::printf("  growth t(random100k) / t(random1k): %.1f (target <= 4)\n", random_100k / random_1k);

    std::printf(
        "\n(e) random100k: read and prepared (RES 1 1), and rendered at 400x400 on 64 threads; thin discs\n");
    const std::string tiny = write_scene(make_scene, scenes.back(), 1, 1, failed);
    bench::Stats prepare;
    double prepare_peak = 0;
    for (int r = 0; r < (quick ? 3 : 11); ++r) {
        const bench::Run run = timed({raytracer.string(), tiny});
        prepare.samples.push_back(run.seconds);
        prepare_peak = std::max(prepare_peak, run.peak_bytes);
    }
    std::printf("  prepare: median %.1f ms (min %.1f), peak %.1f MiB (target: 150 ms, 64 MB)\n",
                prepare.median() * 1e3, prepare.min() * 1e3, prepare_peak / 1048576);
    const bench::Run wide = timed({raytracer.string(), "--threads", "64", scenes.back().name + ".txt"});
    std::printf("  64 threads: %.1f ms, peak %.1f MiB (target: 512 MB)\n", wide.seconds * 1e3,
                wide.peak_bytes / 1048576);
    // Thin discs: their boxes are grown to cull from across the scene down to about 2e-13
    // of its extent (BoxGaps); thinner ones are tried unculled from afar (1e-12: 13 s).
    std::printf("  2,000 random discs t thick (random 2k flattened), 400x400, median of %d:", runs);
    for (const int exponent : {9, 11}) {
        const ScaleScene discs{"discs" + std::to_string(exponent), "discs", exponent, 0};
        const std::string file = write_scene(make_scene, discs, 400, 400, failed);
        bench::Stats time;
        for (int r = 0; r < runs; ++r) time.samples.push_back(timed({raytracer.string(), file}).seconds);
        std::printf(" t = 1e-%d %.1f ms", exponent, time.median() * 1e3);
        std::error_code ignored;
        for (const char* end : {".txt", ".ppm"}) fs::remove(discs.name + end, ignored);
    }
    std::printf("\n");
    for (const ScaleScene& s : scenes) {
        std::error_code ignored;
        for (const char* end : {".txt", ".ppm", "-pov.ppm", "-embree.ppm", "-small.txt", "-small.ppm"})
            fs::remove(s.name + end, ignored);
    }
}
