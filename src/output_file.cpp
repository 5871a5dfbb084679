// The image's file: created before the render, put in place whole when complete. The
// system calls that create, write and rename it are the platform's own file
// (output_file_posix.cpp, output_file_windows.cpp).
#include "raytracer/output_file.h"

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <type_traits>

#include "output_file_parts.h"
#include "raytracer/interrupts.h"
#include "raytracer/shown.h"

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace rt {

namespace fs = std::filesystem;
static_assert(std::is_same_v<NativePath, fs::path::string_type>, "output_file.h names the wrong type");

fs::path temporary_name_in(const fs::path& folder) {
    int local = 0;
    std::uint64_t x = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
    x ^= static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&local)) << 17;
    x ^= static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&folder));
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
    std::string name(kTemporaryPrefix);
    for (int shift = 60; shift >= 0; shift -= 4) name += "0123456789abcdef"[(x >> shift) & 0xF];
    return folder / (name + std::string(kTemporarySuffix));
}

fs::path folder_of(const fs::path& target) { return target.has_parent_path() ? target.parent_path() : "."; }

std::string cannot_create(const std::string& name, const fs::path& folder, int error) {
    std::error_code ec;
    const std::string start = shown(name, kMaxShownPath) + " cannot be created: ";
    if (error == ENAMETOOLONG) return start + "the name or path is too long for the system";
#ifndef _WIN32
    // A folder removed while the program ran (its working folder, say) can still be
    // stat'ed, with no link left; making a file in it fails with EPERM (O_TMPFILE) or ENOENT.
    if (struct stat s{}; ::stat(folder.c_str(), &s) == 0 && s.st_nlink == 0)
        return start + "its folder " + shown(folder.u8string(), kMaxShownPath) + " has been deleted";
#endif
    // exists() fails, rather than says no, where the path cannot be followed: a folder
    // on the way without search permission, a loop of symbolic links.
    if (!fs::exists(folder, ec) && ec)
        return start + "its folder " + shown(folder.u8string(), kMaxShownPath) + " cannot be reached: " +
               (ec.value() == EACCES ? std::string("permission denied") : ec.message());
    if (!fs::exists(folder, ec))
        return start + "its folder " + shown(folder.u8string(), kMaxShownPath) + " does not exist";
    if (!fs::is_directory(folder, ec))
        return start + shown(folder.u8string(), kMaxShownPath) + " is not a folder";
    if (error == EROFS) return start + "its folder is on a read-only file system";
    if (error == EACCES || error == EPERM || error == 0)
        return start + "its folder is not writable (permission denied)";
    return start + std::strerror(error);
}

PendingFile::PendingFile(const char* file_name, Destination destination, bool within_working_folder,
                         int descriptor)
    : name_(file_name == nullptr ? "" : file_name),
      destination_(destination),
      within_working_folder_(within_working_folder) {
    if (destination_ == Destination::Descriptor) {
#ifdef _WIN32
        (void)descriptor;
        error_ = shown(name_, kMaxShownPath) + " cannot be opened: no descriptors are passed on Windows";
#else
        fd_ = descriptor;
        open_ = fd_ > 2;
        if (!open_) error_ = shown(name_, kMaxShownPath) + " is not a descriptor to write into";
#endif
        return;
    }
    if (destination_ == Destination::StandardOutput) {
        if (name_.empty()) name_ = "-";  // else as the user named it (-o /dev/stdout)
#ifdef _WIN32
        (void)_setmode(_fileno(stdout), _O_BINARY);  // no "\n" -> "\r\n" in the image
        file_ = stdout;
#else
        fd_ = 1;
#endif
        open_ = true;
        return;
    }
    if (name_.empty()) {
        error_ = "no file name given";
        return;
    }
    try {
        target_ = fs::u8path(name_).native();  // may throw on names that are not valid UTF-8 (on Windows)
        if (destination_ == Destination::WriteInto) {
#ifdef _WIN32
            file_ = _wfopen(target_.c_str(), L"wb");
            open_ = file_ != nullptr;
#else
            fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
            open_ = fd_ >= 0;
#endif
            if (!open_) error_ = shown(name_, kMaxShownPath) + " cannot be opened: " + std::strerror(errno);
            return;
        }
        open_replacement();
    } catch (const std::exception& e) {
        error_ = shown(name_, kMaxShownPath) + " is not a usable file name: " + e.what();
    }
}

PendingFile::~PendingFile() {
    discard();
#ifndef _WIN32
    if (folder_ >= 0) ::close(folder_);
#endif
}

// Around each write to a stream (standard output, a FIFO, a device): from the first on,
// an interrupt says the image is incomplete rather than not written; once the last
// expected byte is out, it has nothing left to stop (hold_interrupts()). Not before that
// write: a reader that never reads would leave it blocked and deaf to Ctrl+C.
void PendingFile::stream_bytes_ahead() const {
    if (destination_ != Destination::Replace) set_interrupt_output_is_stream(true);
}
void PendingFile::stream_bytes_out(std::size_t size) {
    if (destination_ == Destination::Replace) return;
    written_ += size;
    if (expected_ != 0 && written_ >= expected_) hold_interrupts();
}

std::string PendingFile::write_failure() const {
    const std::string start = shown(name_, kMaxShownPath) + " could not be written in full: ";
    switch (write_error_) {
        case EFBIG:
            return start + "the file size limit was reached (ulimit -f)";
        case ENOSPC:
            return start + "the disk is full";
#ifdef EDQUOT
        case EDQUOT:
            return start + "the disk quota is used up";
#endif
        case EPIPE:
            return start + "the reader closed the pipe";
        default:
            return start + std::strerror(write_error_);
    }
}

void PendingFile::discard() {
    if (!open_) return;
    close_file();
    if (!temporary_.empty()) {
        remove_temporary();
        clear_interrupt_cleanup();
    }
}

std::string PendingFile::commit() {
    if (!open_) return error_.empty() ? shown(name_, kMaxShownPath) + " was already written" : error_;
    std::string error;
    if (write_error_ == 0) hold_interrupts();  // the image is complete: no interrupt may undo it now
    if (write_error_ != 0) {
        error = write_failure();
    } else if (destination_ != Destination::Replace) {
#ifdef _WIN32
        if (std::fflush(file_) != 0) error = shown(name_, kMaxShownPath) + " could not be written in full";
#endif
        close_file();
    } else if (unnamed_) {
        if (link_unnamed(error))
            error.clear();
        else
            error = shown(name_, kMaxShownPath) + " cannot be put in place: " + error;
    } else {
        error = put_in_place();
    }
    if (error.empty()) {
        clear_interrupt_cleanup();
        temporary_.clear();  // it is the target now
    } else {
        release_interrupts();
    }
    discard();
    return error;
}

std::string write_whole_file(const char* file_name, const void* data, std::size_t size) {
    PendingFile file(file_name);
    if (!file.error().empty()) return file.error();
    file.write(data, size);
    return file.commit();
}

}  // namespace rt
