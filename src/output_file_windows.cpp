// The image's file on Windows (output_file.cpp): a named temporary that the system
// deletes when its handle closes until commit() renames it over the target through
// that handle.
#include "raytracer/windows_api.h"  // first: before anything that may include <windows.h>

#include <fcntl.h>
#include <io.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "output_file_parts.h"
#include "raytracer/folder_place.h"
#include "raytracer/interrupts.h"
#include "raytracer/output_file.h"
#include "raytracer/shown.h"

namespace rt {

namespace fs = std::filesystem;

namespace {

// The errno of a CreateFileW failure, for cannot_create(): the one _wfopen would set,
// but for a name too long, which says so.
int errno_of(DWORD error) {
    switch (error) {
        case ERROR_FILENAME_EXCED_RANGE:
            return ENAMETOOLONG;
        case ERROR_FILE_NOT_FOUND:
        case ERROR_PATH_NOT_FOUND:
        case ERROR_INVALID_DRIVE:
        case ERROR_BAD_PATHNAME:
            return ENOENT;
        case ERROR_ACCESS_DENIED:
        case ERROR_SHARING_VIOLATION:
        case ERROR_WRITE_PROTECT:
            return EACCES;
        case ERROR_DISK_FULL:
        case ERROR_HANDLE_DISK_FULL:
            return ENOSPC;
        default:
            return EINVAL;
    }
}

// Sets whether the system deletes the file when its last handle closes: the handle's
// delete disposition, which needs the DELETE access right.
bool set_deleted_on_close(HANDLE handle, bool deleted) {
    FILE_DISPOSITION_INFO disposition{};
    disposition.DeleteFile = deleted ? TRUE : FALSE;
    return SetFileInformationByHandle(handle, FileDispositionInfo, &disposition, sizeof disposition) != 0;
}

// A new file for writing that is deleted when the process ends, however it ends (Ctrl+C,
// the console window closed, the process killed), as Linux's unnamed O_TMPFILE is:
// deleted_on_close says whether the file system took that. Opened to share deletion
// too: where it did not, an interrupt's handler removes the temporary while the render
// still holds it open (interrupts.cpp), which Windows refuses for a file opened by
// _wfopen. On failure, null and errno set.
FILE* create_removable(const wchar_t* path, bool& deleted_on_close) {
    const HANDLE handle = CreateFileW(path, GENERIC_WRITE | DELETE, FILE_SHARE_READ | FILE_SHARE_DELETE,
                                      nullptr, CREATE_ALWAYS, FILE_ATTRIBUTE_NORMAL, nullptr);
    if (handle == INVALID_HANDLE_VALUE) {
        errno = errno_of(GetLastError());
        return nullptr;
    }
    deleted_on_close = set_deleted_on_close(handle, true);
    const int fd = _open_osfhandle(reinterpret_cast<std::intptr_t>(handle), _O_WRONLY | _O_BINARY);
    if (fd < 0) {
        (void)CloseHandle(handle);
        return nullptr;
    }
    FILE* file = _fdopen(fd, "wb");
    if (file == nullptr) (void)_close(fd);
    return file;
}

// Renames the open file over target, replacing it, through its handle (which needs the
// DELETE access right): on failure the file is still the handle's, to delete on close,
// where a rename by name (MoveFileExW) would leave it to a removal by name that another
// program (a virus scanner) may block. On failure, false and why in error.
bool rename_over(HANDLE handle, const std::wstring& target, std::string& error) {
    // A full path (the system reads a relative one differently), but for one in the
    // \\?\ namespace, which libstdc++'s fs::absolute() takes for relative and mangles
    // (\\?\C:\x into C:\?\C:\x).
    fs::path path = target;
    std::error_code ec;
    if (target.rfind(L"\\\\?\\", 0) != 0) path = fs::absolute(path, ec);
    if (ec) path = target;
    const std::wstring& name = path.native();
    // FILE_RENAME_INFO ends in the name, which the system reads up to its NUL: the
    // buffer holds one wchar_t more than the name (FileName[1]), zeroed.
    std::vector<unsigned char> buffer(sizeof(FILE_RENAME_INFO) + name.size() * sizeof(wchar_t));
    auto* info = reinterpret_cast<FILE_RENAME_INFO*>(buffer.data());
    info->ReplaceIfExists = TRUE;
    info->RootDirectory = nullptr;
    info->FileNameLength = static_cast<DWORD>(name.size() * sizeof(wchar_t));
    std::memcpy(info->FileName, name.c_str(), info->FileNameLength);
    if (SetFileInformationByHandle(handle, FileRenameInfo, info, static_cast<DWORD>(buffer.size())))
        return true;
    const DWORD code = GetLastError();
    // A viewer that holds the image open without leave to delete it: a sharing or an
    // access violation, by system and file system (Wine: ERROR_ACCESS_DENIED).
    const bool in_use =
        code == ERROR_SHARING_VIOLATION || code == ERROR_ACCESS_DENIED || code == ERROR_LOCK_VIOLATION;
    error =
        std::string(in_use ? "another program may have it open, or it is protected" : "cannot replace it") +
        " (Windows error " + std::to_string(code) + ")";
    return false;
}

}  // namespace

void PendingFile::open_replacement() {
    // choose_output()'s check once more, just before the file is made: by path, as the
    // rename into place is (no folder handle to make them by here).
    int place_error = 0;
    if (within_working_folder_ &&
        place_of(folder_of(target_).native(), place_error) == FolderPlace::Outside) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its folder is not in the working folder";
        return;
    }
    std::error_code ec;
    if (fs::is_directory(target_, ec)) {
        error_ = shown(name_, kMaxShownPath) + " is a folder";
        return;
    }
    replaces_ = fs::exists(target_, ec);
    open_named(folder_of(target_).native());
}

bool PendingFile::open_unnamed(const NativePath& /*folder*/) { return false; }

void PendingFile::remove_temporary() {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
}

void PendingFile::open_named(const NativePath& folder) {
    temporary_ = temporary_name_in(folder).native();
    if (!set_interrupt_cleanup(temporary_.c_str())) {
        error_ = shown(name_, kMaxShownPath) + " cannot be created: its path is too long";
        return;
    }
    file_ = create_removable(temporary_.c_str(), deleted_on_close_);  // wide names: any Unicode path
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

// Renamed while still open: the file is deleted on close until the rename is done, and
// again if it fails. Closed unchecked: it is unbuffered (open_named()), so every byte
// went out in write(), which checked it. A file system that takes the deletion but not
// its cancelling (some user-mode drivers had that bug) deletes the image on close: then
// an error says so rather than nothing.
std::string PendingFile::put_in_place() {
    const HANDLE handle = reinterpret_cast<HANDLE>(_get_osfhandle(_fileno(file_)));
    std::string error;
    if (deleted_on_close_ && !set_deleted_on_close(handle, false)) {
        error = "cannot be kept (Windows error " + std::to_string(GetLastError()) + ")";
    } else if (!rename_over(handle, target_, error)) {
        error = "cannot be replaced: " + error;
        if (deleted_on_close_) (void)set_deleted_on_close(handle, true);
    }
    (void)std::fclose(file_);
    file_ = nullptr;
    if (error.empty() && deleted_on_close_ && GetFileAttributesW(target_.c_str()) == INVALID_FILE_ATTRIBUTES)
        error = "was deleted by its file system as it was closed (Windows error " +
                std::to_string(GetLastError()) + ")";
    return error.empty() ? error : shown(name_, kMaxShownPath) + " " + error;
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

}  // namespace rt
