// A large scene file read at offsets by the threads that parse it, a chunk of whole
// lines at a time, so that its text is never whole in memory (parse_scene_file(),
// parser.h).
//
// WHY: the first touch of fresh memory is what reading costs (a page fault each 4 KiB,
// or 2 MiB on huge pages): a 26 MB scene read into one array took 19-40 ms on two
// threads, a chunk at a time into one reused buffer per thread 6 ms; and the text never
// adds to the peak of memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string_view>
#include <vector>

namespace rt {

// Whether a file can be read at an offset on this system without moving a shared
// position (pread on POSIX); on Windows a scene file is read as a stream.
#ifdef _WIN32
inline constexpr bool kReadsInPieces = false;
#else
inline constexpr bool kReadsInPieces = true;
#endif

// The size of the regular file open as `in`, asked of the open file, not of its name
// (another file may be renamed over the name meanwhile); nullopt for anything else (a
// pipe, a device, a folder) or where the system does not say.
std::optional<std::uintmax_t> regular_file_size(std::FILE* in);

// The file open as `in`, of `size` bytes when its size was taken. Every read is at an
// offset of its own, so the handle's position stays where it was, and every read is
// from that one file, even where another is renamed over its name meanwhile. A read
// that fails or comes short (the file changed) makes the call return false or nullopt.
class FileAt {
public:
    // The bytes in a chunk (a line longer than this grows the buffer to hold it).
    static constexpr std::size_t kChunkBytes = std::size_t{256} << 10;

    FileAt(std::FILE* in, std::size_t size);
    std::size_t size() const { return size_; }

    // Bytes [offset, offset + n) into out.
    bool read(std::size_t offset, std::size_t n, char* out) const;
    // Where the line after the first LF at or after `at` starts (size() if none).
    std::optional<std::size_t> after_line_feed(std::size_t at) const;
    // Bytes [first, end) as chunks of whole lines, in order: lines(chunk) for each, the
    // bytes read into buffer (reused). A chunk ends after a line end (LF, or CR before
    // another byte than LF) or at end.
    template <typename Lines>
    bool read_lines(std::size_t first, std::size_t end, std::vector<char>& buffer, const Lines& lines) const {
        const auto call = [](const void* f, std::string_view chunk) {
            (*static_cast<const Lines*>(f))(chunk);
        };
        return read_lines(first, end, buffer, call, &lines);
    }
    // Whether nothing follows size() bytes (the file has not grown).
    bool ends_at_size() const;

private:
    // read_lines() with lines(f, chunk) for each chunk: a function pointer, not a
    // std::function, whose header costs each file that includes this one 0.15 s to build.
    bool read_lines(std::size_t first, std::size_t end, std::vector<char>& buffer,
                    void (*lines)(const void* f, std::string_view chunk), const void* f) const;

    int fd_ = -1;
    std::size_t size_ = 0;
};

}  // namespace rt
