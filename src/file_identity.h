// A file's identity whatever names lead to it (hard and symbolic links, "./", 8.3 names):
// what standard_streams.cpp compares files by, and folder_place.cpp folders.
#pragma once

#ifdef _WIN32
#include "raytracer/windows_api.h"
#else
#include <sys/stat.h>
#endif

namespace rt {

#ifdef _WIN32
// The file or folder at path opened for its attributes alone, shared every way (folders
// too: backup semantics); INVALID_HANDLE_VALUE where it cannot be opened.
inline HANDLE open_attributes(const wchar_t* path) {
    return CreateFileW(path, FILE_READ_ATTRIBUTES, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE,
                       nullptr, OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
}
// Volume and file index.
inline bool same_identity(const BY_HANDLE_FILE_INFORMATION& x, const BY_HANDLE_FILE_INFORMATION& y) {
    return x.dwVolumeSerialNumber == y.dwVolumeSerialNumber && x.nFileIndexHigh == y.nFileIndexHigh &&
           x.nFileIndexLow == y.nFileIndexLow;
}
#else
// Device and inode.
inline bool same_identity(const struct stat& x, const struct stat& y) {
    return x.st_dev == y.st_dev && x.st_ino == y.st_ino;
}
#endif

}  // namespace rt
