// Which file a path or a standard stream (0 input, 1 output, 2 error) is, compared by
// identity (POSIX: device and inode; Windows: volume and file index), so that hard and
// symbolic links, "./" and /dev/fd/N name what they are.
#pragma once

#include <string>

namespace rt {

// Whether two paths name one file.
bool same_file(const std::string& a, const std::string& b);
// Whether standard stream `stream` is this file (Windows: a file on disk only).
bool standard_stream_is(int stream, const std::string& file);
// Whether two standard streams are one regular file (not one terminal, say).
bool standard_streams_are_one_file(int a, int b);
// Whether two standard streams are one regular file or one pipe (2>&1 | ...), where
// what is written to the one lands among what is written to the other (not a terminal
// nor a device such as /dev/null). Windows: files on disk only.
bool standard_streams_are_one_stream(int a, int b);
// Whether a standard stream is a folder: closed at the start (main() holds it open on
// one) or given so. Windows: never (a closed stream has no handle at all there).
bool standard_stream_is_folder(int stream);
// Why -o cannot name this path, or empty: a link (/dev/stdout, /dev/fd/N) to a
// standard stream that is closed, said so rather than "a folder".
std::string closed_stream_named(const std::string& path);

}  // namespace rt
