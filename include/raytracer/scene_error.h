// The one kind of error a scene can cause: it knows where it happened, and prints as
// "<file>:<line>: error: <what was found>, <what was expected>" (the file name escaped
// and cut as shown.h says).
#pragma once

#include <stdexcept>
#include <string>

#include "raytracer/shown.h"

namespace rt {

class SceneError : public std::runtime_error {
public:
    // line 0 means the error is about the file as a whole (no line to point at).
    SceneError(const std::string& file, int line, const std::string& what)
        : std::runtime_error(format(file, line, what)) {}

private:
    static std::string format(const std::string& file, int line, const std::string& what) {
        std::string text = escaped(file);  // a path as the user gave it: may hold any byte
        if (line > 0) text += ":" + std::to_string(line);
        return text + ": error: " + what;
    }
};

}  // namespace rt
