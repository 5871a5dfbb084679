// Which file a path or a standard stream is, by identity rather than by name: what
// output_policy.cpp decides by, and main() for the progress line.
#include "raytracer/standard_streams.h"

#include <filesystem>

#include "file_identity.h"
#include "raytracer/shown.h"

#ifdef _WIN32
#include "raytracer/windows_api.h"
#else
#include <sys/stat.h>
#endif

namespace rt {

#ifdef _WIN32
namespace {
namespace fs = std::filesystem;

// A file's identity whatever its names: volume and file index (hard links, case, 8.3 names).
bool identity(const std::string& name, BY_HANDLE_FILE_INFORMATION& info) {
    const HANDLE h = open_attributes(fs::u8path(name).c_str());
    if (h == INVALID_HANDLE_VALUE) return false;
    const bool ok = GetFileInformationByHandle(h, &info) != 0;
    CloseHandle(h);
    return ok;
}

// Whether standard input (stream 0), output (1) or error (2) is a file on disk, and which.
bool stream_identity(int stream, BY_HANDLE_FILE_INFORMATION& info) {
    const HANDLE handle = GetStdHandle(stream == 0   ? STD_INPUT_HANDLE
                                       : stream == 1 ? STD_OUTPUT_HANDLE
                                                     : STD_ERROR_HANDLE);
    return handle != INVALID_HANDLE_VALUE && handle != nullptr && GetFileType(handle) == FILE_TYPE_DISK &&
           GetFileInformationByHandle(handle, &info) != 0;
}
}  // namespace

bool same_file(const std::string& a, const std::string& b) {
    BY_HANDLE_FILE_INFORMATION x{}, y{};
    return identity(a, x) && identity(b, y) && same_identity(x, y);
}

// Whether the standard stream is this file.
bool standard_stream_is(int stream, const std::string& file) {
    BY_HANDLE_FILE_INFORMATION x{}, y{};
    return stream_identity(stream, x) && identity(file, y) && same_identity(x, y);
}

// Whether two standard streams are one file on disk.
bool standard_streams_are_one_file(int a, int b) {
    BY_HANDLE_FILE_INFORMATION x{}, y{};
    return stream_identity(a, x) && stream_identity(b, y) && same_identity(x, y);
}

bool standard_streams_are_one_stream(int a, int b) { return standard_streams_are_one_file(a, b); }

// A closed standard stream has no handle at all here: writing it fails and says so.
bool standard_stream_is_folder(int /*stream*/) { return false; }
std::string closed_stream_named(const std::string& /*path*/) { return {}; }
#else
namespace {
// Whether two standard streams are one file whose type `kind` takes.
template <typename Kind>
bool standard_streams_are_one(int a, int b, Kind kind) {
    struct stat x {
    }, y{};
    return ::fstat(a, &x) == 0 && ::fstat(b, &y) == 0 && kind(x.st_mode) && same_identity(x, y);
}
}  // namespace

bool same_file(const std::string& a, const std::string& b) {
    struct stat x {
    }, y{};
    return ::stat(a.c_str(), &x) == 0 && ::stat(b.c_str(), &y) == 0 && same_identity(x, y);
}

// Whether standard input (stream 0), output (1) or error (2) is this file.
bool standard_stream_is(int stream, const std::string& file) {
    struct stat x {
    }, y{};
    return ::fstat(stream, &x) == 0 && ::stat(file.c_str(), &y) == 0 && same_identity(x, y);
}

bool standard_streams_are_one_file(int a, int b) {
    return standard_streams_are_one(a, b, [](mode_t mode) { return S_ISREG(mode); });
}

bool standard_streams_are_one_stream(int a, int b) {
    return standard_streams_are_one(
        a, b, [](mode_t mode) { return S_ISREG(mode) || S_ISFIFO(mode) || S_ISSOCK(mode); });
}

// Whether standard stream 0, 1 or 2 is a folder: closed at the start (main() opens it on /), or given so.
bool standard_stream_is_folder(int stream) {
    struct stat s {};
    return ::fstat(stream, &s) == 0 && S_ISDIR(s.st_mode);
}

// Why -o cannot name this path, or empty: a link (/dev/stdout, /dev/fd/N) to a standard
// stream that is closed, said so rather than "a folder" (the one main() holds it open on).
std::string closed_stream_named(const std::string& path) {
    const char* const names[] = {"input", "output", "error"};
    struct stat s {};
    for (const int stream : {0, 1, 2})
        if (::lstat(path.c_str(), &s) == 0 && S_ISLNK(s.st_mode) && standard_stream_is_folder(stream) &&
            standard_stream_is(stream, path))
            return shown(path, kMaxShownPath) + " is standard " + names[stream] +
                   ", which is closed (or a folder), expected " +
                   (stream == 1 ? "a pipe or a file" : "another file");
    return {};
}
#endif

}  // namespace rt
