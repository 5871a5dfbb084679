// The benchmark's table of the program's size and build time (issue 14, target 5):
//   (f) the lines of src/ and include/ (.h and .cpp, blank lines included; src/grade,
//       the grader, aside), how many files, the longest; and raytracer.exe configured
//       and built from scratch as a user does (a fresh build folder, Release, the
//       generator and compiler of this build, the default options): wall time of rounds.
// Run in the benchmark's scratch folder (the working directory), where it builds.
#pragma once

#include <filesystem>
#include <string>

struct BuildSetup {
    std::filesystem::path source;  // the repository's top folder
    std::filesystem::path cmake;   // the cmake program
    std::string generator;         // CMAKE_GENERATOR
    std::string make_program;      // CMAKE_MAKE_PROGRAM (may be empty)
    std::string compiler;          // CMAKE_CXX_COMPILER
};

void build_table(const BuildSetup& setup, bool quick, bool& failed);
