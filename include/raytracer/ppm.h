// Binary (P6) and text (P3) PPM files. The save functions keep the handout's template
// signatures (width, height, file name, pixels: width*height*3 bytes, top row first),
// but report failure instead of printing it, and never leave a partial file: they
// write a temporary file beside the target and rename it into place when complete.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "raytracer/image.h"
#include "raytracer/row_sink.h"

namespace rt {

// A file written in two steps, for writing an image that is still to be rendered: the
// constructor creates a temporary file beside the target, so that an unwritable target
// is known before the render and only one file is ever created; commit() closes it
// and renames it over the target. A file not committed (an error, an exception during
// the render) is removed by the destructor, so nothing is left behind.
class PendingFile {
public:
    explicit PendingFile(const char* file_name);
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;
    ~PendingFile();

    // Why the temporary file could not be created; empty when it was.
    const std::string& error() const { return error_; }
    // Announces the final size, so that the file system allocates it at once: a hint,
    // ignored where unsupported (see ppm.cpp for why it pays).
    void expect_size(std::uint64_t bytes);
    // Appends the bytes (only when error() is empty); a failure is reported by commit().
    void write(const void* data, std::size_t size);
    // Closes the temporary file and moves it onto the target. Returns an empty string on
    // success, else what went wrong; the temporary is removed either way.
    std::string commit();

private:
    void discard();

    std::string name_;  // as given, for messages
    std::filesystem::path target_, temporary_;
    std::FILE* file_ = nullptr;  // the temporary, while ours
    bool write_failed_ = false;
    std::string error_;
};

// A P6 image written into a pending file as its rows come (a RowSink for render_to()): the
// header at once, the rows as they come, then commit() checks that all came and
// commits the file (same return convention as PendingFile::commit()).
class P6Writer final : public RowSink {
public:
    P6Writer(PendingFile& file, int width, int height);
    void rows(const std::uint8_t* bytes, std::size_t size) override;
    std::string commit();

private:
    PendingFile& file_;
    std::size_t expected_ = 0, written_ = 0;  // pixel bytes
};

// Writes a P6 image into a pending file (its error() must be empty) and commits it.
std::string save_imageP6(PendingFile& file, int width, int height, const unsigned char* pixels);

// Each returns an empty string on success, else what went wrong (for a message).
std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels);
std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels);

// Checks, before a long render, that save_imageP6 will be able to create file_name:
// creates and removes a temporary file beside it. Same return convention.
std::string check_writable(const char* file_name);

// Reads a binary P6 file with maxval 255 (comments allowed in the header). Returns
// false and says why in error when the file cannot be read or is not such a file.
bool read_ppm(const std::string& file_name, Image& image, std::string& error);

}  // namespace rt
