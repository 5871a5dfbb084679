// PPM output, after the course's ppm.cpp template, made safe: a failed or interrupted
// write never leaves a partial image nor clobbers an existing one.
#include "raytracer/ppm.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>
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

// A name beside the target, so that the final rename stays on one file system.
fs::path temporary_name_for(const fs::path& target) {
    std::random_device random;
    std::ostringstream suffix;
    suffix << ".partial-" << std::hex << random() << random();
    fs::path name = target;
    name += suffix.str();
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

template <typename WriteBody>
std::string save_atomically(const char* file_name, WriteBody write_body) {
    PendingFile file(file_name);
    if (!file.error().empty()) return file.error();
    write_body(file.stream());
    return file.commit();
}

void write_P6(std::ostream& out, int width, int height, const unsigned char* pixels) {
    out << "P6\n" << width << ' ' << height << "\n255\n";
    out.write(reinterpret_cast<const char*>(pixels),
              static_cast<std::streamsize>(width) * static_cast<std::streamsize>(height) * 3);
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
        out_.open(temporary_, std::ios::binary | std::ios::trunc);
        if (!out_) {
            error_ = cannot_create(name_, target_);
            return;
        }
        pending_ = true;
    } catch (const std::exception& e) {
        error_ = "'" + name_ + "' is not a usable file name: " + e.what();
    }
}

PendingFile::~PendingFile() { discard(); }

void PendingFile::discard() {
    if (!pending_) return;
    pending_ = false;
    out_.close();
    std::error_code ignored;
    fs::remove(temporary_, ignored);
}

std::string PendingFile::commit() {
    if (!pending_) return error_.empty() ? "'" + name_ + "' was already written" : error_;
    out_.close();
    if (!out_) {
        discard();
        return "'" + name_ + "' could not be written in full (is the disk full?)";
    }
    std::string error;
    if (!replace_file(temporary_, target_, error)) {
        discard();
        return "'" + name_ + "' cannot be replaced: " + error;
    }
    pending_ = false;
    return {};
}

std::string save_imageP6(PendingFile& file, int width, int height, const unsigned char* pixels) {
    if (!file.error().empty()) return file.error();
    write_P6(file.stream(), width, height, pixels);
    return file.commit();
}

std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels) {
    return save_atomically(file_name, [&](std::ofstream& out) { write_P6(out, width, height, pixels); });
}

std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels) {
    return save_atomically(file_name, [&](std::ofstream& out) {
        out << "P3\n" << width << ' ' << height << "\n255\n";
        const unsigned char* p = pixels;
        for (int row = 0; row < height; ++row) {
            for (int column = 0; column < width; ++column, p += 3)
                out << ' ' << int{p[0]} << ' ' << int{p[1]} << ' ' << int{p[2]};
            out << '\n';
        }
    });
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
