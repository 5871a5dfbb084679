#include "raytracer/file_pieces.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <sys/stat.h>
#include <sys/types.h>
#ifdef _WIN32
#include <stdio.h>  // _fileno
#else
#include <unistd.h>  // pread
#endif

namespace rt {

std::optional<std::uintmax_t> regular_file_size(std::FILE* in) {
#ifdef _WIN32
    struct _stat64 status {};
    if (_fstat64(_fileno(in), &status) != 0 || (status.st_mode & _S_IFMT) != _S_IFREG) return std::nullopt;
#else
    struct stat status {};
    if (::fstat(fileno(in), &status) != 0 || !S_ISREG(status.st_mode)) return std::nullopt;
#endif
    if (status.st_size < 0) return std::nullopt;
    return static_cast<std::uintmax_t>(status.st_size);
}

#ifdef _WIN32
FileAt::FileAt(std::FILE*, std::size_t size) : size_(size) {}
bool FileAt::read(std::size_t, std::size_t, char*) const { return false; }
bool FileAt::ends_at_size() const { return false; }
#else
FileAt::FileAt(std::FILE* in, std::size_t size) : fd_(fileno(in)), size_(size) {}

// pread may return fewer bytes than asked: it is called again for the rest.
bool FileAt::read(std::size_t offset, std::size_t n, char* out) const {
    while (n > 0) {
        const ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(offset));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        const auto k = static_cast<std::size_t>(got);
        out += k, offset += k, n -= k;
    }
    return true;
}

bool FileAt::ends_at_size() const {
    char byte = 0;
    ssize_t got = 0;
    do got = ::pread(fd_, &byte, 1, static_cast<off_t>(size_));
    while (got < 0 && errno == EINTR);
    return got == 0;
}
#endif

std::optional<std::size_t> FileAt::after_line_feed(std::size_t at) const {
    char window[1 << 14];
    for (; at < size_; at += sizeof window) {
        const std::size_t n = std::min(sizeof window, size_ - at);
        if (!read(at, n, window)) return std::nullopt;
        if (const void* lf = std::memchr(window, '\n', n))
            return at + static_cast<std::size_t>(static_cast<const char*>(lf) - window) + 1;
    }
    return size_;
}

bool FileAt::read_lines(std::size_t first, std::size_t end, std::vector<char>& buffer,
                        void (*lines)(const void* f, std::string_view chunk), const void* f) const {
    std::size_t held = 0;  // bytes of a line begun in the chunks before
    for (std::size_t at = first; at < end;) {
        const std::size_t n = std::min(kChunkBytes, end - at);
        if (buffer.size() < held + n) buffer.resize(held + n);
        if (!read(at, n, buffer.data() + held)) return false;
        const std::size_t before = held;
        at += n, held += n;
        // Whole lines: up to the last line end whose line is known to end there (a CR
        // as the last byte read may be the first of a CR LF). The bytes held before
        // hold no line end but that CR: only the new ones and it are looked at, so a
        // line of L bytes costs L, not L^2 / kChunkBytes.
        std::size_t whole = at == end ? held : 0;
        for (std::size_t i = held; whole == 0 && i > 0 && i >= before; --i) {
            const char c = buffer[i - 1];
            if (c == '\n' || (c == '\r' && i < held)) whole = i;
        }
        if (whole == 0) continue;  // one line goes on: read on
        lines(f, std::string_view(buffer.data(), whole));
        std::memmove(buffer.data(), buffer.data() + whole, held - whole);
        held -= whole;
    }
    return true;
}

}  // namespace rt
