// raytracer.exe's command line: options anywhere, in either form (--threads=N or
// --threads N), "--" ending them; every mistake is one message for a usage error.
#pragma once

#include <string>

namespace rt {

struct CommandLine {
    enum class Action { Render, Help, Version, Wrong };
    enum class Progress { WhenTerminal, Always, Never };

    Action action = Action::Wrong;
    std::string scene_file;
    bool output_given = false;  // -o / --output: overrides the scene's OUTPUT
    std::string output;         // "-": standard output
    unsigned threads = 0;       // 0: the default
    Progress progress = Progress::WhenTerminal;
    bool reference = false;  // --reference: through the reference path (render.h)
    std::string error;       // when Wrong: "<what was found>, expected <what>"
};

CommandLine parse_command_line(int argc, const char* const* argv);

}  // namespace rt
