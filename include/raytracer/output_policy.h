// Where the image may be written (README, "Where the image goes"). A scene file is data
// that may come from anywhere, so its OUTPUT may only name a regular file in or below
// the working folder; the user may name any path with -o, which overrides OUTPUT.
#pragma once

#include <string>

#include "raytracer/output_file.h"

namespace rt {

struct OutputChoice {
    std::string path;  // the file to write; "-" for standard output
    bool named_by_user = false;
    Destination destination = Destination::Replace;
    int descriptor = -1;  // the one Destination::Descriptor writes into
    // Why the path is refused, as "<the path shown> <what it is>, expected <what>";
    // empty when it is not.
    std::string refusal;
};

// scene_output: the scene's OUTPUT; user_output: -o's path, or nullptr when not given;
// scene_file: the scene file as named ("-": standard input), which is never replaced.
OutputChoice choose_output(const std::string& scene_output, const std::string* user_output,
                           const std::string& scene_file);

}  // namespace rt
