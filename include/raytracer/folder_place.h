// Where a folder lies against the working folder: whether a scene's OUTPUT, confined to
// the working folder and below it, may be written there (output_policy.cpp checks it
// before the render, PendingFile again on the folder it holds open).
#pragma once

#include "raytracer/output_file.h"

namespace rt {

// In the working folder or below it; elsewhere; not there (nothing to leave through: the
// image's file says it is missing); or not known, a step of the way cannot be opened
// (error: why, as the system's error code).
enum class FolderPlace { Inside, Outside, Missing, Unknown };

// The folder named by a path relative to the working folder, its links followed.
FolderPlace place_of(const NativePath& folder, int& error);

#ifndef _WIN32
// An open folder (a descriptor of open_folder()).
FolderPlace place_of(int folder, int& error);
// The folder at path opened to reach it and its entries by descriptor (openat(), linkat(),
// renameat()), not to read it: where a later change of the path (a folder on the way
// replaced by a link) cannot move what is written. -1 and errno where it fails.
int open_folder(const char* path);
#endif

}  // namespace rt
