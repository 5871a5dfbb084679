#include "raytracer/command_line.h"

#include <algorithm>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "raytracer/shown.h"

namespace rt {
namespace {

constexpr unsigned kMaxThreads = 1024;

bool parse_threads(const std::string& text, unsigned& threads) {
    if (text.empty()) return false;
    unsigned long n = 0;  // of any length, leading zeros too: held just past the largest allowed
    for (const char c : text) {
        if (c < '0' || c > '9') return false;
        n = std::min(n * 10 + static_cast<unsigned long>(c - '0'), kMaxThreads + 1UL);
    }
    if (n == 0 || n > kMaxThreads) return false;
    threads = static_cast<unsigned>(n);
    return true;
}

// The options that take a value: their long and short names.
bool takes_value(std::string_view name) { return name == "--threads" || name == "--output" || name == "-o"; }
// The options that take none.
bool is_flag(std::string_view name) {
    return name == "--progress" || name == "--quiet" || name == "--reference" || name == "--help" ||
           name == "-h" || name == "--version";
}

struct Parser {
    CommandLine line;
    std::vector<std::string> files;
    bool help = false, version = false;
    std::string help_as;  // --help or -h

    bool wrong(const std::string& what) {
        line.action = CommandLine::Action::Wrong;
        line.error = what;
        return false;
    }

    // A second value for one setting is refused rather than one of them silently taken
    // (say, a script's -o before the user's own).
    bool twice(std::string_view name, const std::string& first, const std::string& second) {
        return wrong(std::string(name) + " given twice (" + shown(first) + " and " + shown(second) +
                     "), expected it once");
    }

    bool option(std::string_view name, const std::string* value) {
        if (name == "--threads") {
            if (line.threads != 0) return twice(name, std::to_string(line.threads), *value);
            if (!parse_threads(*value, line.threads))
                return wrong("--threads " + shown(*value) + ", expected a whole number from 1 to 1024");
        } else if (name == "--output" || name == "-o") {
            if (line.output_given) return twice("-o/--output", line.output, *value);
            if (value->empty())
                return wrong(std::string(name) + " with an empty path, expected a file path or -");
            line.output_given = true;
            line.output = *value;
        } else if (name == "--progress" || name == "--quiet") {
            const auto wanted =
                name == "--progress" ? CommandLine::Progress::Always : CommandLine::Progress::Never;
            if (line.progress != CommandLine::Progress::WhenTerminal && line.progress != wanted)
                return wrong("--progress and --quiet together, expected at most one of them");
            line.progress = wanted;
        } else if (name == "--reference") {
            line.reference = true;
        } else if (name == "--help" || name == "-h") {
            help = true;
            help_as = name;  // as the user spelled it, for a message
        } else if (name == "--version") {
            version = true;
        } else {
            return wrong("unknown option " + shown(name) + ", expected a scene file or a known option");
        }
        return true;
    }

    bool parse(int argc, const char* const* argv) {
        bool options_ended = false;
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            if (options_ended || arg.size() < 2 || arg[0] != '-') {
                files.push_back(arg);
                continue;
            }
            if (arg == "--") {
                options_ended = true;
                continue;
            }
            const std::size_t equals = arg.rfind("--", 0) == 0 ? arg.find('=') : std::string::npos;
            const std::string name = arg.substr(0, equals);
            if (!takes_value(name)) {
                if (equals != std::string::npos && is_flag(name))
                    return wrong(shown(name) + " takes no value, expected " + name);
                if (!option(name, nullptr)) return false;
                continue;
            }
            std::string value;
            if (equals != std::string::npos) {
                value = arg.substr(equals + 1);
            } else if (i + 1 < argc) {
                value = argv[++i];
            } else {
                std::string what = name;
                what += " without a value, expected ";
                what += name;
                what += name == "--threads" ? " N" : " PATH";
                return wrong(what);
            }
            if (!option(name, &value)) return false;
        }
        return true;
    }

    void decide() {
        if (help || version) {
            const bool alone = files.empty() && !line.output_given && line.threads == 0 &&
                               line.progress == CommandLine::Progress::WhenTerminal && !line.reference &&
                               !(help && version);
            if (!alone) {
                const std::string option = help ? help_as : "--version";
                wrong(option + " with other arguments, expected " + option +
                      " alone, or options and one scene file without it");
                return;
            }
            line.action = help ? CommandLine::Action::Help : CommandLine::Action::Version;
            return;
        }
        if (files.empty()) {
            wrong("no scene file given, expected exactly one scene file");
        } else if (files.size() > 1) {
            wrong("more than one argument (" + shown(files[0]) + " and " + shown(files[1]) +
                  "), expected exactly one scene file");
        } else if (files[0].empty()) {
            wrong("an empty scene file name, expected exactly one scene file");
        } else {
            line.action = CommandLine::Action::Render;
            line.scene_file = files[0];
        }
    }
};

}  // namespace

CommandLine parse_command_line(int argc, const char* const* argv) {
    Parser parser;
    if (parser.parse(argc, argv)) parser.decide();
    return parser.line;
}

}  // namespace rt
