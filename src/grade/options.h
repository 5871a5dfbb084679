// The grader's command line.
#pragma once

#include <filesystem>
#include <string>

namespace grade {

struct Options {
    std::filesystem::path raytracer;  // empty: raytracer.exe beside the grader
    std::filesystem::path keys;       // empty: keys/ beside the scene folder
    std::filesystem::path scenes;     // the folder of *.txt scenes
    std::string only;                 // one scene's name without .txt; empty: all
    double timeout_seconds = 60;      // per scene
    std::filesystem::path diff_dir;   // empty: no difference pictures
    std::filesystem::path html;       // empty: no HTML page
    bool help = false;
};

// Fills options from argv; returns an empty string, or what is wrong with the command line.
std::string parse_command_line(int argc, char** argv, Options& options);

// The --help text: usage, the pass rule, the exit statuses.
std::string help_text(const std::string& default_scenes);

}  // namespace grade
