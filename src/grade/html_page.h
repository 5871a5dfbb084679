// The grader's HTML page: the marks table and each failing scene's difference picture,
// one self-contained file (the pictures are PNG files it references by relative path)
// that any browser shows.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene_grading.h"

namespace grade {

// pictures[i] is the PNG of results[i], or empty. Returns an empty string, or why the page
// could not be written.
std::string write_html_page(const std::filesystem::path& page, const std::vector<SceneResult>& results,
                            const std::vector<std::filesystem::path>& pictures, const std::string& summary);

}  // namespace grade
