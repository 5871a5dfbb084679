// PPM output, after the course's ppm.cpp template, made safe: a failed or interrupted
// write never leaves a partial image nor clobbers an existing one.
#include "raytracer/ppm.h"

#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>
#elif defined(__linux__)
#include <fcntl.h>  // fallocate()
#endif

namespace rt {
namespace {

namespace fs = std::filesystem;

// Moves from onto to, replacing to if it exists. POSIX rename() does that atomically;
// on Windows std::filesystem::rename is not guaranteed to replace an existing file
// with every standard library, so MoveFileExW is asked to explicitly.
bool replace_file(const fs::path& from, const fs::path& to, std::string& error) {
#ifdef _WIN32
    if (MoveFileExW(from.c_str(), to.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
        return true;
    error = "cannot replace it (Windows error " + std::to_string(GetLastError()) + ")";
    return false;
#else
    std::error_code ec;
    fs::rename(from, to, ec);
    if (!ec) return true;
    error = ec.message();
    return false;
#endif
}

// A name beside the target, so that the final rename stays on one file system, and
// that no other run picks at the same time: the target's name and 64 bits mixed
// (splitmix64's finaliser) from the clock's nanoseconds and addresses that address-space
// randomisation makes differ between processes.
// WHY not std::random_device and an ostringstream: together 0.03 to 0.07 ms here (the
// device instruction traps in this virtual machine; a first stream sets up locales).
fs::path temporary_name_for(const fs::path& target) {
    int local = 0;
    std::uint64_t x = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
    x ^= static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&local)) << 17;
    x ^= static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&target));
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
    std::string suffix = ".partial-";
    for (int shift = 60; shift >= 0; shift -= 4) suffix += "0123456789abcdef"[(x >> shift) & 0xF];
    fs::path name = target;
    name += suffix;
    return name;
}

// Why a file could not be created at target, as precisely as the file system tells.
std::string cannot_create(const std::string& name, const fs::path& target) {
    std::error_code ec;
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (!fs::exists(folder, ec))
        return "'" + name + "' cannot be created: its folder '" + folder.u8string() + "' does not exist";
    if (!fs::is_directory(folder, ec))
        return "'" + name + "' cannot be created: '" + folder.u8string() + "' is not a folder";
    return "'" + name + "' cannot be created: its folder is not writable";
}

// An existing folder of the target's name cannot be replaced by the image.
std::string check_target(const char* file_name, const fs::path& target) {
    std::error_code ec;
    if (fs::is_directory(target, ec)) return "'" + std::string(file_name) + "' is a folder";
    return {};
}

std::FILE* create_binary(const fs::path& path) {
#ifdef _WIN32
    return _wfopen(path.c_str(), L"wb");  // wide names: any Unicode path
#else
    return std::fopen(path.c_str(), "wb");
#endif
}

}  // namespace

PendingFile::PendingFile(const char* file_name) : name_(file_name == nullptr ? "" : file_name) {
    if (name_.empty()) {
        error_ = "no file name given";
        return;
    }
    // u8path may throw on names that are not valid UTF-8 (on Windows).
    try {
        target_ = fs::u8path(name_);
        if (error_ = check_target(name_.c_str(), target_); !error_.empty()) return;
        // Creating a file beside the target is the only sure test that it can be
        // written: permissions, read-only media and ACLs all have their say.
        temporary_ = temporary_name_for(target_);
        file_ = create_binary(temporary_);
        if (file_ == nullptr) {
            error_ = cannot_create(name_, target_);
            return;
        }
        // Every write is one large block: no copy through a buffer.
        std::setvbuf(file_, nullptr, _IONBF, 0);
    } catch (const std::exception& e) {
        error_ = "'" + name_ + "' is not a usable file name: " + e.what();
    }
}

PendingFile::~PendingFile() { discard(); }

void PendingFile::discard() {
    if (file_ == nullptr) return;
    std::fclose(file_);
    file_ = nullptr;
    std::error_code ignored;
    fs::remove(temporary_, ignored);
}

// WHY: on ext4 (delayed allocation, auto_da_alloc) renaming a new file over an existing
// one first allocates and flushes the new file's blocks, inside rename(): about 0.5 ms
// for a 400x400 image on the build machine, a quarter of the whole run of the floor
// program (docs/speed.md). Blocks allocated up front by fallocate() are not delayed,
// so the rename does not wait for them. Elsewhere nothing is done.
void PendingFile::expect_size(std::uint64_t bytes) {
#if defined(__linux__)
    if (file_ != nullptr && bytes > 0) (void)fallocate(fileno(file_), 0, 0, static_cast<off_t>(bytes));
#else
    (void)bytes;
#endif
}

void PendingFile::write(const void* data, std::size_t size) {
    if (file_ == nullptr || write_failed_) return;
    if (std::fwrite(data, 1, size, file_) != size) write_failed_ = true;
}

std::string PendingFile::commit() {
    if (file_ == nullptr) return error_.empty() ? "'" + name_ + "' was already written" : error_;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    std::string error;
    if (write_failed_ || !closed) {
        error = "'" + name_ + "' could not be written in full (is the disk full?)";
    } else if (!replace_file(temporary_, target_, error)) {
        error = "'" + name_ + "' cannot be replaced: " + error;
    } else {
        return {};
    }
    std::error_code ignored;
    fs::remove(temporary_, ignored);
    return error;
}

P6Writer::P6Writer(PendingFile& file, int width, int height)
    : file_(file), expected_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    if (!file_.error().empty()) return;
    const std::string header = "P6\n" + std::to_string(width) + ' ' + std::to_string(height) + "\n255\n";
    file_.expect_size(header.size() + expected_);
    file_.write(header.data(), header.size());
}

void P6Writer::rows(const std::uint8_t* bytes, std::size_t size) {
    if (!file_.error().empty()) return;
    file_.write(bytes, size);
    written_ += size;
}

std::string P6Writer::commit() {
    if (!file_.error().empty()) return file_.error();
    if (written_ != expected_) {  // not committed: the file's destructor removes it
        return "the image's rows came incomplete (" + std::to_string(written_) + " of " +
               std::to_string(expected_) + " bytes)";
    }
    return file_.commit();
}

std::string save_imageP6(PendingFile& file, int width, int height, const unsigned char* pixels) {
    P6Writer writer(file, width, height);  // commit() reports the file's error, if any
    writer.rows(pixels, static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    return writer.commit();
}

std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels) {
    PendingFile file(file_name);
    return save_imageP6(file, width, height, pixels);
}

std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels) {
    PendingFile file(file_name);
    if (!file.error().empty()) return file.error();
    std::ostringstream out;
    out << "P3\n" << width << ' ' << height << "\n255\n";
    const unsigned char* p = pixels;
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column, p += 3)
            out << ' ' << int{p[0]} << ' ' << int{p[1]} << ' ' << int{p[2]};
        out << '\n';
    }
    const std::string text = out.str();
    file.write(text.data(), text.size());
    return file.commit();
}

std::string check_writable(const char* file_name) { return PendingFile(file_name).error(); }

bool read_ppm(const std::string& file_name, Image& image, std::string& error) {
    std::ifstream in(fs::u8path(file_name), std::ios::binary);
    if (!in) {
        error = "cannot open '" + file_name + "'";
        return false;
    }
    // Header: P6, width, height, maxval, separated by whitespace and # comments,
    // then exactly one whitespace byte before the pixels.
    std::string fields[4];
    for (std::string& field : fields) {
        int c = in.get();
        while (c != EOF && (std::isspace(c) || c == '#')) {
            if (c == '#')
                while (c != EOF && c != '\n') c = in.get();
            c = in.get();
        }
        while (c != EOF && !std::isspace(c)) {
            field += static_cast<char>(c);
            c = in.get();
        }
    }
    long long width = 0, height = 0;
    try {
        width = std::stoll(fields[1]);
        height = std::stoll(fields[2]);
    } catch (const std::exception&) {
        width = height = 0;
    }
    if (fields[0] != "P6" || fields[3] != "255" || width <= 0 || height <= 0 ||
        width * height > (1LL << 31)) {
        error = "'" + file_name + "' is not a binary PPM (P6) with maxval 255";
        return false;
    }
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.rgb.assign(static_cast<std::size_t>(width * height * 3), 0);
    in.read(reinterpret_cast<char*>(image.rgb.data()), static_cast<std::streamsize>(image.rgb.size()));
    if (in.gcount() != static_cast<std::streamsize>(image.rgb.size())) {
        error = "'" + file_name + "' is shorter than its header says";
        return false;
    }
    return true;
}

}  // namespace rt
