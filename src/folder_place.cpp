// Where a folder lies against the working folder (folder_place.h): on POSIX systems by
// walking up from the folder itself, on Windows by its final path.
#include "raytracer/folder_place.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "file_identity.h"

#ifndef _WIN32
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace rt {

#ifdef _WIN32
namespace {

namespace fs = std::filesystem;

// The folder's path with the links and junctions on the way resolved: the one the system
// gives it once opened (some standard libraries' fs::canonical leaves links as they are
// here). False where the folder cannot be opened.
bool resolved_folder(const fs::path& folder, fs::path& resolved) {
    const HANDLE handle = open_attributes(folder.c_str());
    if (handle == INVALID_HANDLE_VALUE) return false;
    std::wstring path(32768, L'\0');  // the longest path Windows has
    const DWORD size = GetFinalPathNameByHandleW(handle, path.data(), static_cast<DWORD>(path.size()),
                                                 FILE_NAME_NORMALIZED | VOLUME_NAME_DOS);
    CloseHandle(handle);
    if (size == 0 || size >= path.size()) return false;
    path.resize(size);
    resolved = path;
    return true;
}

}  // namespace

// Its resolved path against the working folder's (GetFinalPathNameByHandleW has no
// PATH_MAX of its own to fail on).
FolderPlace place_of(const NativePath& folder, int& error) {
    fs::path resolved, working;
    if (!resolved_folder(folder, resolved)) {
        error = static_cast<int>(GetLastError());
        return error == ERROR_FILE_NOT_FOUND || error == ERROR_PATH_NOT_FOUND ? FolderPlace::Missing
                                                                              : FolderPlace::Unknown;
    }
    std::error_code ec;
    const fs::path current = fs::current_path(ec);
    if (ec || !resolved_folder(current, working)) {
        error = ec ? ec.value() : static_cast<int>(GetLastError());
        return FolderPlace::Unknown;
    }
    const auto [mismatch, ignored] =
        std::mismatch(working.begin(), working.end(), resolved.begin(), resolved.end());
    return mismatch == working.end() ? FolderPlace::Inside : FolderPlace::Outside;
}
#else
namespace {

// O_PATH (Linux) opens a folder this user may not read: only its identity and its
// entries by name are needed.
#ifdef O_PATH
constexpr int kFolderOnly = O_PATH | O_DIRECTORY | O_CLOEXEC;
#else
constexpr int kFolderOnly = O_RDONLY | O_DIRECTORY | O_CLOEXEC;
#endif

}  // namespace

int open_folder(const char* path) { return ::open(path, kFolderOnly); }

// Walked up by its "..", folder by folder, until the working folder (by device and
// inode) or the root, its own "..". WHY by identity and not by resolved path: a resolved
// path may be longer than PATH_MAX (deep folders, long links), where fs::canonical()
// fails, and the check must not pass where it cannot be made.
FolderPlace place_of(int folder, int& error) {
    struct stat working {};
    struct stat here {};
    if (::stat(".", &working) != 0 || ::fstat(folder, &here) != 0) {
        error = errno;
        return FolderPlace::Unknown;
    }
    int fd = ::fcntl(folder, F_DUPFD_CLOEXEC, 0);  // the folder `here` is
    if (fd < 0) error = errno;
    FolderPlace place = FolderPlace::Unknown;
    while (fd >= 0) {
        if (same_identity(here, working)) {
            place = FolderPlace::Inside;
            break;
        }
        const int up = ::openat(fd, "..", kFolderOnly);
        struct stat above {};
        const bool known = up >= 0 && ::fstat(up, &above) == 0;
        if (!known) error = errno;
        ::close(fd);
        fd = up;
        if (!known) break;
        if (same_identity(above, here)) {  // the root is its own ".."
            place = FolderPlace::Outside;
            break;
        }
        here = above;
    }
    if (fd >= 0) ::close(fd);
    return place;
}

FolderPlace place_of(const NativePath& folder, int& error) {
    const int fd = open_folder(folder.c_str());
    if (fd < 0) {
        error = errno;
        return error == ENOENT || error == ENOTDIR ? FolderPlace::Missing : FolderPlace::Unknown;
    }
    const FolderPlace place = place_of(fd, error);
    ::close(fd);
    return place;
}
#endif

}  // namespace rt
