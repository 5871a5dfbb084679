// PPM output, after the course's ppm.cpp template, made safe: a failed or interrupted
// write never leaves a partial image nor clobbers an existing one. And PPM input, for the
// tests and the grader (read_ppm()).
#include "raytracer/ppm.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <memory>
#include <system_error>

#include "raytracer/output_file.h"
#include "raytracer/shown.h"

namespace rt {

P6Writer::P6Writer(PendingFile& file, int width, int height)
    : file_(file), pixel_bytes_expected_(bytes_of_pixels(width, height)) {
    if (!file_.error().empty()) {
        failed_.store(true, std::memory_order_relaxed);
        return;
    }
    const std::string header = "P6\n" + std::to_string(width) + ' ' + std::to_string(height) + "\n255\n";
    file_.expect_size(header.size() + pixel_bytes_expected_);
    file_.write(header.data(), header.size());
    if (file_.write_failed()) failed_.store(true, std::memory_order_relaxed);
}

void P6Writer::write_rows(const std::uint8_t* bytes, std::size_t size) {
    if (!file_.error().empty()) return;
    file_.write(bytes, size);
    pixel_bytes_written_ += size;
    if (file_.write_failed()) failed_.store(true, std::memory_order_relaxed);
}

std::string P6Writer::commit() {
    if (!file_.error().empty()) return file_.error();
    if (pixel_bytes_written_ != pixel_bytes_expected_) {  // not committed: the file's destructor removes it
        return "the image's rows came incomplete (" + std::to_string(pixel_bytes_written_) + " of " +
               std::to_string(pixel_bytes_expected_) + " bytes)";
    }
    return file_.commit();
}

std::string save_imageP6(PendingFile& file, int width, int height, const unsigned char* pixels) {
    P6Writer writer(file, width, height);  // commit() reports the file's error, if any
    writer.write_rows(pixels, bytes_of_pixels(width, height));
    return writer.commit();
}

std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels) {
    PendingFile file(file_name);
    return save_imageP6(file, width, height, pixels);
}

std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels) {
    std::string text = "P3\n" + std::to_string(width) + ' ' + std::to_string(height) + "\n255\n";
    const unsigned char* p = pixels;
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width * 3; ++column) text += ' ' + std::to_string(int{*p++});
        text += '\n';
    }
    return write_whole_file(file_name, text.data(), text.size());
}

namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// The file open to read, or null with `error` saying why.
File open_to_read(const std::string& file_name, std::string& error) {
    std::error_code ec;
    const std::filesystem::file_status status =
        std::filesystem::status(std::filesystem::u8path(file_name), ec);
    if (std::filesystem::is_directory(status)) {
        error = shown(file_name, kMaxShownPath) + " is a folder";
        return {nullptr, &std::fclose};
    }
    // A FIFO would block the reader until something writes it (a grader's key: for good).
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
        error = shown(file_name, kMaxShownPath) + " is not a regular file (a FIFO, device or socket)";
        return {nullptr, &std::fclose};
    }
    errno = 0;
#ifdef _WIN32
    std::FILE* const file = _wfopen(std::filesystem::u8path(file_name).c_str(), L"rb");  // any Unicode name
#else
    std::FILE* const file = std::fopen(file_name.c_str(), "rb");
#endif
    if (file == nullptr)
        error = "cannot open " + shown(file_name, kMaxShownPath) +
                (errno != 0 ? std::string(": ") + std::strerror(errno) : "");
    return {file, &std::fclose};
}

// Netpbm's P6 header: the two bytes "P6" first, then width, height and maxval as
// decimal numbers, each after whitespace and # comments and ending at one of them, and
// exactly one whitespace byte (the one that ends maxval) before the pixels. False, with
// `error` set, where the file is not a binary PPM with maxval 255 of at most 2^31 - 1
// pixels: a header that a PPM reader would refuse ("P6\n600abc 600\n...") is not taken
// for the numbers it starts with.
bool read_header(std::FILE* in, const std::string& file_name, int& width, int& height, std::size_t& bytes,
                 std::string& error) {
    const std::string name = shown(file_name, kMaxShownPath);
    const auto refuse = [&error, &name] {
        error = name + " is not a binary PPM (P6) with maxval 255";
        return false;
    };
    // Bytes read from the file, up to the header's limit (an endless comment or run of
    // blanks ends there); then EOF.
    bytes = 0;
    const auto next = [in, &bytes] { return bytes++ < kMaxPpmHeaderBytes ? std::fgetc(in) : EOF; };
    if (next() != 'P' || next() != '6') return refuse();
    long long numbers[3] = {};
    std::string digits[3];
    for (int k = 0; k < 3; ++k) {
        int c = next();
        if (c == EOF || (!std::isspace(c) && c != '#')) return refuse();  // "P61", "600abc"
        while (c != EOF && (std::isspace(c) || c == '#')) {
            if (c == '#')
                while (c != EOF && c != '\n') c = next();
            c = next();
        }
        if (bytes > kMaxPpmHeaderBytes) {
            error = name + " has a header of over " + std::to_string(kMaxPpmHeaderBytes >> 10) +
                    " KiB, expected a binary PPM (P6)";
            return false;
        }
        for (; c != EOF && std::isdigit(c) != 0; c = next()) {
            if (numbers[k] < (1LL << 40)) numbers[k] = numbers[k] * 10 + (c - '0');  // larger is refused
            digits[k] += static_cast<char>(c);
        }
        // Width and height end at whitespace or a comment, which the next separator
        // reads again; maxval ends at the one whitespace byte before the pixels.
        const bool ended = c != EOF && (std::isspace(c) != 0 || (k < 2 && c == '#'));
        if (digits[k].empty() || !ended) return refuse();
        if (k < 2) std::ungetc(c, in), --bytes;
    }
    const long long w = numbers[0], h = numbers[1];
    if (numbers[2] != 255) return refuse();
    if (w <= 0 || h <= 0) {
        error = name + " is a P6 of " + escaped(digits[0], kMaxShownToken) + "x" +
                escaped(digits[1], kMaxShownToken) + " pixels, expected at least one";
        return false;
    }
    if (w > std::numeric_limits<int>::max() / h) {
        error = name + " is a P6 of " + escaped(digits[0], kMaxShownToken) + "x" +
                escaped(digits[1], kMaxShownToken) + " pixels, more than the 2^31 - 1 read";
        return false;
    }
    width = static_cast<int>(w), height = static_cast<int>(h);
    return true;
}

}  // namespace

bool read_ppm_size(const std::string& file_name, int& width, int& height, std::string& error) {
    const File in = open_to_read(file_name, error);
    std::size_t header = 0;
    return in && read_header(in.get(), file_name, width, height, header, error);
}

bool read_ppm(const std::string& file_name, Image& image, std::string& error, std::uint64_t* bytes_after) {
    const File in = open_to_read(file_name, error);
    std::size_t header = 0;
    if (!in || !read_header(in.get(), file_name, image.width, image.height, header, error)) return false;
    // Grown as the bytes come, doubling, so that a header claiming more pixels than the
    // file holds costs about the file's size in memory, not the header's.
    const std::size_t size = bytes_of_pixels(image.width, image.height);
    image.rgb.clear();
    for (std::size_t got = 0; got < size;) {
        const std::size_t chunk = std::min(size - got, std::max(got, std::size_t{1} << 20));
        image.rgb.resize(got + chunk);
        const std::size_t read = std::fread(image.rgb.data() + got, 1, chunk, in.get());
        got += read;
        if (read < chunk) {
            error = shown(file_name, kMaxShownPath) + " is shorter than its header says";
            return false;
        }
    }
    if (bytes_after != nullptr) {
        // From the file's size, not read: a file with gigabytes (or a sparse terabyte)
        // after its pixels costs no time. At least one where a byte follows the pixels.
        *bytes_after = 0;
        if (std::fgetc(in.get()) != EOF) {
            std::error_code ec;
            const std::uintmax_t total = std::filesystem::file_size(std::filesystem::u8path(file_name), ec);
            const std::uintmax_t used = header + size;
            *bytes_after = !ec && total > used ? total - used : 1;
        }
    }
    return true;
}

}  // namespace rt
