#include "raytracer/file_pieces.h"

#include <algorithm>
#include <atomic>
#include <cerrno>

#include "raytracer/helper_pool.h"

#ifndef _WIN32
#include <sys/types.h>
#include <unistd.h>  // pread
#endif

namespace rt {

#ifdef _WIN32
bool read_in_pieces(std::FILE*, std::size_t, unsigned, char*) { return false; }
#else
namespace {

// Bytes [offset, offset + size) of file descriptor fd into out; whether they were all
// there. pread may return fewer bytes than asked: it is called again for the rest.
bool read_at(int fd, std::size_t offset, std::size_t size, char* out) {
    while (size > 0) {
        const ssize_t got = ::pread(fd, out, size, static_cast<off_t>(offset));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        const auto n = static_cast<std::size_t>(got);
        out += n, offset += n, size -= n;
    }
    return true;
}

// Whether nothing follows byte `offset` of fd.
bool ends_at(int fd, std::size_t offset) {
    char byte = 0;
    ssize_t got = 0;
    do got = ::pread(fd, &byte, 1, static_cast<off_t>(offset));
    while (got < 0 && errno == EINTR);
    return got == 0;
}

}  // namespace

bool read_in_pieces(std::FILE* in, std::size_t size, unsigned threads, char* bytes) {
    const int fd = fileno(in);
    const std::size_t pieces = std::max(threads, 1U), piece = size / pieces + 1;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> whole{true};
    auto read_pieces = [&] {
        for (std::size_t k; whole && (k = next++) < pieces;) {
            const std::size_t first = std::min(size, k * piece), last = std::min(size, first + piece);
            if (!read_at(fd, first, last - first, bytes + first)) whole = false;
        }
    };
    HelperPool::Job helpers;
    helpers.start(static_cast<unsigned>(pieces) - 1, read_pieces);
    read_pieces();
    helpers.finish();
    return whole && ends_at(fd, size);
}
#endif

}  // namespace rt
