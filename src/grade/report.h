// The grader's text report on stdout: a row per scene as it is graded, the details of a
// failing scene (where its image differs), and the summary line with the marks.
#pragma once

#include <string>
#include <vector>

#include "scene_grading.h"

namespace grade {

constexpr int kMarksPerScene = 2;

void print_header();
// picture: the difference picture written for the scene, or empty.
void print_scene(const SceneResult& result, const std::string& picture);
// Returns the summary line (also for the HTML page) after printing it.
std::string print_summary(const std::vector<SceneResult>& results);

// "3 pixels differ: 3 off by one level (allowed)"-style sentence of a judgement.
std::string describe_differences(const Judgement& judgement);
// "(375, 200): key 0 0 0, got 0 0 255", and the other outcome of a known ambiguous pixel.
std::string describe_pixel(const PixelDifference& difference);

}  // namespace grade
