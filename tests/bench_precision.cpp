// bench_precision: the speed-vs-error report of issue 4. For every course scene and
// every hard case (scenes/hard/) and each precision (float, double, long double) it
// renders the scene several times in this process, takes the median time, and
// measures the error: against the course's key for course scenes, against the long
// double render for hard cases. It writes OUT/precision-report.{md,csv,svg}.
//
//   bench_precision [--quick] [--repeats N] [--out DIR] [--course DIR] [--hard DIR]
//
// --quick (for CI) renders course scenes at a quarter and hard cases at half their
// size, once each; keys then no longer fit, so course scenes are measured against long
// double too. It prints the figures and always exits 0 unless it cannot run: it is a
// report, not a timed test.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "precision.h"
#include "precision_report.h"
#include "raytracer/parser.h"
#include "raytracer/ppm.h"

namespace fs = std::filesystem;

namespace {

struct Options {
    bool quick = false;
    int repeats = 5;
    fs::path out = ".";
    fs::path course = RAYTRACER_COURSE_SCENES;
    fs::path hard = RAYTRACER_HARD_SCENES;
};

std::vector<fs::path> scenes_in(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().extension() == ".txt") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// The median of `repeats` renders, in milliseconds; the last image is returned too.
double median_ms(const rt::Scene& scene, precision::Real real, int repeats, rt::Image& image) {
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        image = precision::render(scene, real);
        times.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    const std::size_t n = times.size();
    return n % 2 == 1 ? times[n / 2] : (times[n / 2 - 1] + times[n / 2]) / 2;
}

void measure(const fs::path& file, const std::string& kind, const Options& options,
             std::vector<report::Row>& rows) {
    rt::Scene scene = rt::load_scene(file.string());
    const int divisor = !options.quick ? 1 : kind == "course" ? 4 : 2;
    scene.columns = std::max(1, scene.columns / divisor);
    scene.rows = std::max(1, scene.rows / divisor);

    rt::Image key;
    bool have_key = false;
    if (kind == "course" && !options.quick) {
        std::string error;
        const std::string stem = file.stem().string();
        const fs::path key_path =
            file.parent_path().parent_path() / "keys" / ("key" + stem.substr(4) + ".ppm");
        have_key = rt::read_ppm(key_path.string(), key, error);
        if (!have_key) std::fprintf(stderr, "bench_precision: %s, using long double\n", error.c_str());
    }

    // Long double first: it is the reference where there is no key.
    const precision::Real order[] = {precision::Real::kLongDouble, precision::Real::kDouble,
                                     precision::Real::kFloat};
    rt::Image truth;
    for (precision::Real real : order) {
        report::Row row;
        row.scene = file.stem().string();
        row.kind = kind;
        row.real = real;
        row.width = scene.columns;
        row.height = scene.rows;
        rt::Image image;
        row.median_ms = median_ms(scene, real, options.repeats, image);
        if (real == precision::Real::kLongDouble) truth = image;
        row.reference = have_key ? "key" : "long double";
        row.error = precision::error_of(image, have_key ? key : truth);
        std::printf("%-22s %-6s %-11s %9.2f ms  %7lld pixels differ (%.4f%%)  largest %3d  PSNR %s dB\n",
                    row.scene.c_str(), kind.c_str(), precision::name_of(real), row.median_ms,
                    row.error.differing_pixels, precision::differing_percent(row.error),
                    row.error.largest_difference, report::psnr_text(row.error.psnr).c_str());
        std::fflush(stdout);
        rows.push_back(row);
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool has_value = i + 1 < argc;
        if (a == "--quick") {
            options.quick = true;
            options.repeats = 1;
        } else if (a == "--repeats" && has_value) {
            options.repeats = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--out" && has_value) {
            options.out = argv[++i];
        } else if (a == "--course" && has_value) {
            options.course = argv[++i];
        } else if (a == "--hard" && has_value) {
            options.hard = argv[++i];
        } else {
            std::fprintf(
                stderr,
                "usage: bench_precision [--quick] [--repeats N] [--out DIR] [--course DIR] [--hard DIR]\n");
            return 2;
        }
    }

    std::vector<report::Row> rows;
    try {
        for (const fs::path& f : scenes_in(options.course)) measure(f, "course", options, rows);
        for (const fs::path& f : scenes_in(options.hard)) measure(f, "hard", options, rows);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_precision: %s\n", e.what());
        return 1;
    }
    if (rows.empty()) {
        std::fprintf(stderr, "bench_precision: no scenes in %s or %s\n", options.course.string().c_str(),
                     options.hard.string().c_str());
        return 1;
    }

    const std::string mode = options.quick
                                 ? "quick mode: course scenes at 1/4 size, hard cases at 1/2, 1 run"
                                 : "full size, median of " + std::to_string(options.repeats) + " runs";
    const std::string notes =
        "Generated by `tests/bench_precision` (" + mode +
        "), one thread, on the machine that ran it: times are comparable within a table, not across "
        "machines. "
        "Error is against the course key for course scenes (\"key\") and against the long double render "
        "otherwise; **!** marks a scene outside the 0.01% bar. Regenerate with "
        "`build/ci/tests/bench_precision --repeats 7 --out docs` (see docs/precision.md).";
    std::error_code ec;
    fs::create_directories(options.out, ec);
    const bool ok =
        report::write_file((options.out / "precision-report.md").string(),
                           report::markdown(rows, "Precision report: speed against error", notes)) &&
        report::write_file((options.out / "precision-report.csv").string(), report::csv(rows)) &&
        report::write_file((options.out / "precision-report.svg").string(),
                           report::svg(rows, "Render time against error, per scene and precision"));
    if (!ok) {
        std::fprintf(stderr, "bench_precision: cannot write the report into %s\n",
                     options.out.string().c_str());
        return 1;
    }
    std::printf("wrote %s/precision-report.{md,csv,svg}\n", options.out.string().c_str());
    return 0;
}
