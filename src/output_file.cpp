// The image's file: created before the render, put in place whole when complete.
#include "raytracer/output_file.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <type_traits>

#include "raytracer/interrupts.h"
#include "raytracer/shown.h"

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <fcntl.h>
#include <io.h>
#include <windows.h>
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace rt {
namespace {

namespace fs = std::filesystem;
static_assert(std::is_same_v<NativePath, fs::path::string_type>, "output_file.h names the wrong type");

// A short hidden name in the target's folder: short, so that it fits the folder's name
// limit whatever the target's length (a 255-byte target name is legal); in the same
// folder, so that the final rename stays on one file system; and one no other run picks
// at the same time: 64 bits mixed (splitmix64's finaliser) from the clock's nanoseconds
// and addresses that address-space randomisation makes differ between processes.
// WHY not std::random_device: the device instruction traps in this virtual machine.
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

// Why a file could not be created in folder, as precisely as the file system tells.
std::string cannot_create(const std::string& name, const fs::path& folder, int error) {
    std::error_code ec;
    const std::string start = shown(name, kMaxShownPath) + " cannot be created: ";
    if (error == ENAMETOOLONG) return start + "the name or path is too long for the system";
    if (!fs::exists(folder, ec))
        return start + "its folder " + shown(folder.u8string(), kMaxShownPath) + " does not exist";
    if (!fs::is_directory(folder, ec))
        return start + shown(folder.u8string(), kMaxShownPath) + " is not a folder";
    if (error == EROFS) return start + "its folder is on a read-only file system";
    if (error == EACCES || error == EPERM || error == 0)
        return start + "its folder is not writable (permission denied)";
    return start + std::strerror(error);
}

#ifdef _WIN32
bool replace_file(const fs::path& from, const fs::path& to, std::string& error) {
    // std::filesystem::rename is not guaranteed to replace an existing file on Windows
    // with every standard library, so MoveFileExW is asked to explicitly.
    if (MoveFileExW(from.c_str(), to.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
        return true;
    error = "cannot replace it (Windows error " + std::to_string(GetLastError()) + ")";
    return false;
}
#else
bool replace_file(const fs::path& from, const fs::path& to, std::string& error) {
    if (std::rename(from.c_str(), to.c_str()) == 0) return true;
    error = std::strerror(errno);
    return false;
}
#endif

}  // namespace

PendingFile::PendingFile(const char* file_name, Destination destination)
    : name_(file_name == nullptr ? "" : file_name), destination_(destination) {
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

PendingFile::~PendingFile() { discard(); }

#ifndef _WIN32
void PendingFile::open_replacement() {
    struct stat existing {};
    if (::stat(target_.c_str(), &existing) == 0) {
        if (S_ISDIR(existing.st_mode)) {
            error_ = shown(name_, kMaxShownPath) + " is a folder";
            return;
        }
        if (!S_ISREG(existing.st_mode)) {
            error_ = shown(name_, kMaxShownPath) + " is not a regular file (a device, FIFO or socket)";
            return;
        }
        replaces_ = true;
        keep_mode_ = existing.st_mode & 07777;
    }
    const NativePath folder = folder_of(target_).native();
    if (!open_unnamed(folder)) open_named(folder);
    if (open_ && replaces_) {
        // Its owner and group too, where this user may give them (root replacing another
        // user's file); chown() clears set-user-ID bits, so it comes before chmod().
        (void)!fchown(fd_, existing.st_uid, existing.st_gid);
        (void)fchmod(fd_, static_cast<mode_t>(keep_mode_));
    }
}

bool PendingFile::open_unnamed(const NativePath& folder) {
#if defined(__linux__) && defined(O_TMPFILE)
    // The tests set this to exercise the named temporary of other systems here.
    const char* named = std::getenv("RAYTRACER_NAMED_TEMPORARY");
    if (named != nullptr && std::strcmp(named, "1") == 0) return false;
    fd_ = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    if (fd_ >= 0) {
        open_ = unnamed_ = true;
        return true;
    }
    // Where the file system or the kernel cannot, a named temporary does.
    if (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL) return false;
    error_ = cannot_create(name_, folder, errno);
    return true;
#else
    (void)folder;
    return false;
#endif
}

void PendingFile::open_named(const NativePath& folder) {
    temporary_ = temporary_name_in(folder).native();
    if (!set_interrupt_cleanup(temporary_.c_str())) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its path is too long";
        return;
    }
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0) {
        const int error = errno;
        clear_interrupt_cleanup();
        error_ = cannot_create(name_, folder, error);
        return;
    }
    open_ = true;
}

// Gives the unnamed file its name. A new target is linked in one step; an existing one
// is replaced by a link under a temporary name renamed over it (rename is atomic, link
// cannot replace), a window of two system calls in which only SIGKILL would leave the
// temporary.
bool PendingFile::link_unnamed(std::string& error) {
    const std::string proc_path = "/proc/self/fd/" + std::to_string(fd_);
    auto link_as = [&](const fs::path& name) {
        if (::linkat(AT_FDCWD, proc_path.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
#ifdef AT_EMPTY_PATH
        if (errno == ENOENT &&  // no /proc: the same by the descriptor (needs privilege)
            ::linkat(fd_, "", AT_FDCWD, name.c_str(), AT_EMPTY_PATH) == 0)
            return 0;
#endif
        return errno;
    };
    if (!replaces_) {
        const int failed = link_as(target_);
        if (failed == 0) return true;
        if (failed != EEXIST) {
            error = std::strerror(failed);
            return false;
        }
    }
    temporary_ = temporary_name_in(folder_of(target_)).native();
    if (!set_interrupt_cleanup(temporary_.c_str())) {
        error = "its path is too long";
        return false;
    }
    if (const int failed = link_as(temporary_); failed != 0) {
        error = std::strerror(failed);
        temporary_.clear();
        clear_interrupt_cleanup();
        return false;
    }
    return replace_file(temporary_, target_, error);
}

void PendingFile::close_file() {
    if (fd_ > 2) (void)::close(fd_);
    fd_ = -1;
    open_ = false;
}

void PendingFile::write(const void* data, std::size_t size) {
    if (!open_ || write_error_ != 0) return;
    stream_bytes_ahead();
    const char* bytes = static_cast<const char*>(data);
    const std::size_t total = size;
    while (size > 0) {
        const ssize_t done = ::write(fd_, bytes, size);
        if (done < 0 && errno == EINTR) continue;
        if (done <= 0) {
            write_error_ = done < 0 ? errno : ENOSPC;
            return;
        }
        bytes += done;
        size -= static_cast<std::size_t>(done);
    }
    stream_bytes_out(total);
}

// WHY: on ext4 (delayed allocation, auto_da_alloc) renaming a new file over an existing
// one first allocates and flushes the new file's blocks, inside rename(): about 0.5 ms
// for a 400x400 image on the build machine, a quarter of the whole run of the floor
// program (docs/speed.md). Blocks allocated up front by fallocate() are not delayed,
// so the rename does not wait for them. Elsewhere nothing is done.
void PendingFile::expect_size(std::uint64_t bytes) {
    expected_ = bytes;
#if defined(__linux__)
    if (open_ && destination_ == Destination::Replace && bytes > 0)
        (void)fallocate(fd_, 0, 0, static_cast<off_t>(bytes));
#else
    (void)bytes;
#endif
}
#endif  // !_WIN32

#ifdef _WIN32
void PendingFile::open_replacement() {
    std::error_code ec;
    if (fs::is_directory(target_, ec)) {
        error_ = shown(name_, kMaxShownPath) + " is a folder";
        return;
    }
    replaces_ = fs::exists(target_, ec);
    open_named(folder_of(target_).native());
}

bool PendingFile::open_unnamed(const NativePath& /*folder*/) { return false; }

void PendingFile::open_named(const NativePath& folder) {
    temporary_ = temporary_name_in(folder).native();
    if (!set_interrupt_cleanup(temporary_.c_str())) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its path is too long";
        return;
    }
    file_ = _wfopen(temporary_.c_str(), L"wb");  // wide names: any Unicode path
    if (file_ == nullptr) {
        const int error = errno;
        clear_interrupt_cleanup();
        error_ = cannot_create(name_, folder, error);
        return;
    }
    std::setvbuf(file_, nullptr, _IONBF, 0);  // every write is one large block: no copy
    open_ = true;
}

bool PendingFile::link_unnamed(std::string& error) {
    error = "unnamed files are not supported here";
    return false;
}

void PendingFile::close_file() {
    if (file_ != nullptr && file_ != stdout) (void)std::fclose(file_);
    if (file_ == stdout) (void)std::fflush(stdout);
    file_ = nullptr;
    open_ = false;
}

void PendingFile::write(const void* data, std::size_t size) {
    if (!open_ || write_error_ != 0) return;
    stream_bytes_ahead();
    if (std::fwrite(data, 1, size, file_) != size)
        write_error_ = errno != 0 ? errno : ENOSPC;
    else
        stream_bytes_out(size);
}

void PendingFile::expect_size(std::uint64_t bytes) { expected_ = bytes; }
#endif  // _WIN32

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
        std::error_code ignored;
        fs::remove(temporary_, ignored);
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
#ifdef _WIN32
        const bool closed = std::fclose(file_) == 0;
        file_ = nullptr;
#else
        const bool closed = ::close(fd_) == 0;
        fd_ = -1;
#endif
        if (!closed)
            error = shown(name_, kMaxShownPath) + " could not be written in full (is the disk full?)";
        else if (!replace_file(temporary_, target_, error))
            error = shown(name_, kMaxShownPath) + " cannot be replaced: " + error;
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

}  // namespace rt
