// Binary (P6) and text (P3) PPM files. The save functions keep the handout's template
// signatures (width, height, file name, pixels: width*height*3 bytes, top row first),
// but report failure instead of printing it, and never leave a partial file: they
// write through a PendingFile (output_file.h), put in place only when complete.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "raytracer/image.h"
#include "raytracer/row_sink.h"

namespace rt {

class PendingFile;  // output_file.h

// A P6 image written into a pending file as its rows come (a RowSink for render_to()): the
// header at once, the rows as they come, then commit() checks that all came and
// commits the file (same return convention as PendingFile::commit()).
class P6Writer final : public RowSink {
public:
    P6Writer(PendingFile& file, int width, int height);
    void write_rows(const std::uint8_t* bytes, std::size_t size) override;
    bool failed() const override { return failed_.load(std::memory_order_relaxed); }
    std::string commit();

private:
    PendingFile& file_;
    std::size_t pixel_bytes_expected_ = 0, pixel_bytes_written_ = 0;
    std::atomic<bool> failed_{false};  // file_'s error, for the render's threads
};

// Writes a P6 image into a pending file (its error() must be empty) and commits it.
std::string save_imageP6(PendingFile& file, int width, int height, const unsigned char* pixels);

// Each returns an empty string on success, else what went wrong (for a message).
std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels);
std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels);

// The longest P6 header read, comments included: a longer one is refused, so that a
// file of endless comment costs a reader no time.
inline constexpr std::size_t kMaxPpmHeaderBytes = std::size_t{64} << 10;

// Reads a binary P6 file with maxval 255 (comments allowed in the header). Returns
// false and says why in error when the file cannot be read or is not such a file.
// Where bytes_after is given, it counts the bytes after the pixels (a P6 file has none),
// from the file's size.
bool read_ppm(const std::string& file_name, Image& image, std::string& error,
              std::uint64_t* bytes_after = nullptr);
// Reads only the header of such a file: its width and height, without the memory its
// pixels would take (a grader checks the size first).
bool read_ppm_size(const std::string& file_name, int& width, int& height, std::string& error);

}  // namespace rt
