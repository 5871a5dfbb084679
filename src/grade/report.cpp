#include "report.h"

#include <cstdio>
#include <string>

#include "raytracer/shown.h"

namespace grade {
namespace {

using rt::plural;

std::string rgb(const std::uint8_t* c) {
    return std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]);
}

// The name padded to `width` characters (UTF-8: a character's bytes after its first are
// not counted), so that the table's columns line up.
std::string padded(const std::string& name, std::size_t width) {
    std::size_t characters = 0;
    for (const char c : name) characters += (static_cast<unsigned char>(c) & 0xC0U) != 0x80U ? 1 : 0;
    return name + std::string(characters < width ? width - characters : 0, ' ');
}

}  // namespace

void print_header() {
    std::printf("%-20s %9s %11s %8s  %-6s %s\n", "scene", "differing", "unexplained", "time s", "result",
                "marks");
}

std::string describe_differences(const Judgement& j) {
    if (j.differing == 0) return "identical to the key";
    std::string text = plural(j.differing, "pixel differs", "pixels differ") + " from the key";
    if (j.too_many_steps())
        text += "; " + std::to_string(j.truncation_steps) + " by one level, more than the " +
                std::to_string(kMaxTruncationSteps) +
                " truncation steps allowed (a systematic difference: rounding, not truncating?)";
    else if (j.truncation_steps > 0)
        text += "; " + std::to_string(j.truncation_steps) + " by one level (allowed)";
    if (j.ambiguous > 0)
        text += "; " + std::to_string(j.ambiguous) + " known ambiguous showing the other outcome (allowed)";
    if (j.unexplained > 0) text += "; " + std::to_string(j.unexplained) + " unexplained";
    return text;
}

std::string describe_pixel(const PixelDifference& d) {
    std::string text = "(" + std::to_string(d.x) + ", " + std::to_string(d.y) + "): key " + rgb(d.key) +
                       ", got " + rgb(d.got);
    if (d.ambiguous) text += " (a known ambiguous pixel: its other outcome is " + rgb(d.other.data()) + ")";
    return text;
}

void print_scene(const SceneResult& r, const std::string& picture) {
    const int marks = r.passed() ? kMarksPerScene : 0;
    const char* result = r.passed() ? "pass" : "FAIL";
    if (!r.problem.empty()) {
        std::printf("%s %9s %11s %8.3f  %-6s %d/%d  %s\n", padded(rt::controls_escaped(r.name), 20).c_str(),
                    "-", "-", r.seconds, result, marks, kMarksPerScene,
                    rt::controls_escaped(r.problem).c_str());
    } else {
        std::printf("%s %9lld %11lld %8.3f  %-6s %d/%d\n", padded(rt::controls_escaped(r.name), 20).c_str(),
                    r.judgement.differing, r.judgement.unexplained, r.seconds, result, marks, kMarksPerScene);
    }
    for (const std::string& note : r.notes) std::printf("    note: %s\n", rt::controls_escaped(note).c_str());
    if (r.problem.empty() && !r.judgement.passed()) {
        const Judgement& j = r.judgement;
        const Box& b = j.unexplained_box;
        // The largest of the pixels that fail it: an allowed ambiguous pixel's is no reason.
        std::printf("    %s, largest %d levels\n", describe_differences(j).c_str(), j.largest_failing);
        if (!b.empty())
            std::printf(
                "    the unexplained pixels lie in x %d..%d, y %d..%d (column, row from the top-left)\n",
                b.left, b.right, b.top, b.bottom);
        for (const PixelDifference& d : j.first_unexplained)
            std::printf("    %s\n", describe_pixel(d).c_str());
        if (j.unexplained > static_cast<long long>(j.first_unexplained.size()))
            std::printf("    ... and %lld more\n",
                        j.unexplained - static_cast<long long>(j.first_unexplained.size()));
    }
    if (!picture.empty())
        std::printf("    picture (key | yours | difference): %s\n", rt::controls_escaped(picture).c_str());
    std::fflush(stdout);
}

std::string print_summary(const std::vector<SceneResult>& results) {
    long long passed = 0, not_rendered = 0, ungradable = 0, not_run = 0;
    for (const SceneResult& r : results) {
        passed += r.passed() ? 1 : 0;
        not_run += r.scratch_unwritable ? 1 : 0;
        ungradable += r.ungradable && !r.scratch_unwritable ? 1 : 0;
        not_rendered += r.problem.empty() || r.ungradable ? 0 : 1;
    }
    const long long scenes = static_cast<long long>(results.size());
    std::string line = "marks " + std::to_string(kMarksPerScene * passed) + "/" +
                       std::to_string(kMarksPerScene * scenes) + ": ";
    if (passed == scenes) {
        line += scenes == 1 ? "the scene passes" : "all " + std::to_string(scenes) + " scenes pass";
    } else {
        line += std::to_string(passed) + " of " + plural(scenes, "scene passes", "scenes pass");
        if (ungradable > 0)
            line += "; " + std::to_string(ungradable) + " without a readable scene or key to grade by";
        if (not_run > 0)
            line += "; " + std::to_string(not_run) + " not run: the grader could not make a folder";
        if (not_rendered > 0) line += "; " + std::to_string(not_rendered) + " gave no image to compare";
        if (scenes - passed - not_rendered - ungradable - not_run > 0)
            line += "; " +
                    plural(scenes - passed - not_rendered - ungradable - not_run, "differs", "differ") +
                    " beyond the rule";
    }
    line += passed == scenes ? ": PASS" : ": FAIL";
    std::printf("%s\n", line.c_str());
    return line;
}

}  // namespace grade
