// The image's file on POSIX systems (output_file.cpp): created unnamed where Linux can
// (O_TMPFILE) and linked into place, elsewhere a named temporary renamed over the target.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "output_file_parts.h"
#include "raytracer/folder_place.h"
#include "raytracer/interrupts.h"
#include "raytracer/output_file.h"
#include "raytracer/shown.h"

namespace rt {

namespace fs = std::filesystem;

void PendingFile::open_replacement() {
    const fs::path target(target_);
    const NativePath folder = folder_of(target).native();
    // A bare name's folder is the working folder itself, which AT_FDCWD names as surely.
    folder_ = target.has_parent_path() ? open_folder(folder.c_str()) : AT_FDCWD;
    if (folder_ == -1) {
        const int error = errno;
        error_ = cannot_create(name_, folder, error);
        return;
    }
    // The same check as choose_output()'s, now on the folder every later step uses.
    int place_error = 0;
    if (within_working_folder_ && folder_ != AT_FDCWD &&
        place_of(folder_, place_error) != FolderPlace::Inside) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its folder is not in the working folder";
        return;
    }
    target_ = target.filename().native();
    if (target_.empty()) target_ = ".";  // "/": the folder itself
    struct stat existing {};
    if (::fstatat(folder_, target_.c_str(), &existing, 0) == 0) {
        if (S_ISDIR(existing.st_mode)) {
            error_ = shown(name_, kMaxShownPath) + " is a folder";
            return;
        }
        if (!S_ISREG(existing.st_mode)) {
            error_ = shown(name_, kMaxShownPath) + " is not a regular file (a device, FIFO or socket)";
            return;
        }
        replaces_ = true;
        // Not set-user-ID, set-group-ID or sticky: an image is no program.
        keep_mode_ = existing.st_mode & 0777;
    }
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
    fd_ = ::openat(folder_, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
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
    temporary_ = temporary_name_in({}).native();
    if (!set_interrupt_cleanup(folder_, temporary_.c_str())) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its path is too long";
        return;
    }
    fd_ = ::openat(folder_, temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0) {
        const int error = errno;
        clear_interrupt_cleanup();
        temporary_.clear();
        error_ = cannot_create(name_, folder, error);
        return;
    }
    open_ = true;
}

void PendingFile::remove_temporary() { (void)::unlinkat(folder_, temporary_.c_str(), 0); }

// Renames the temporary over the target, in the folder held open; on failure, false and
// why in error.
bool PendingFile::replace_target(std::string& error) {
    if (::renameat(folder_, temporary_.c_str(), folder_, target_.c_str()) == 0) return true;
    error = std::strerror(errno);
    return false;
}

// Gives the unnamed file its name. A new target is linked in one step; an existing one
// is replaced by a link under a temporary name renamed over it (rename is atomic, link
// cannot replace), a window of two system calls in which only SIGKILL would leave the
// temporary.
bool PendingFile::link_unnamed(std::string& error) {
    const std::string proc_path = "/proc/self/fd/" + std::to_string(fd_);
    auto link_as = [&](const NativePath& name) {
        if (::linkat(AT_FDCWD, proc_path.c_str(), folder_, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
#ifdef AT_EMPTY_PATH
        if (errno == ENOENT &&  // no /proc: the same by the descriptor (needs privilege)
            ::linkat(fd_, "", folder_, name.c_str(), AT_EMPTY_PATH) == 0)
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
    temporary_ = temporary_name_in({}).native();
    if (!set_interrupt_cleanup(folder_, temporary_.c_str())) {
        error = "its path is too long";
        return false;
    }
    if (const int failed = link_as(temporary_); failed != 0) {
        error = std::strerror(failed);
        temporary_.clear();
        clear_interrupt_cleanup();
        return false;
    }
    return replace_target(error);
}

void PendingFile::close_file() {
    if (fd_ > 2) (void)::close(fd_);
    fd_ = -1;
    open_ = false;
}

// Closed first: a file system may report a failed write only at close (NFS).
std::string PendingFile::put_in_place() {
    const bool closed = ::close(fd_) == 0;
    fd_ = -1;
    if (!closed) return shown(name_, kMaxShownPath) + " could not be written in full (is the disk full?)";
    std::string error;
    if (!replace_target(error)) return shown(name_, kMaxShownPath) + " cannot be replaced: " + error;
    return {};
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
// one first allocates and flushes the new file's blocks, inside rename(): for a 400x400
// image about a quarter of a process that only writes it. Blocks allocated up front by
// fallocate() are not delayed, so the rename does not wait for them. Elsewhere nothing
// is done.
void PendingFile::expect_size(std::uint64_t bytes) {
    expected_ = bytes;
#if defined(__linux__)
    if (open_ && destination_ == Destination::Replace && bytes > 0)
        (void)fallocate(fd_, 0, 0, static_cast<off_t>(bytes));
#else
    (void)bytes;
#endif
}

}  // namespace rt
