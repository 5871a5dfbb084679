// What the image's file (output_file.cpp) shares with the half of it that makes system
// calls, written once a platform: output_file_posix.cpp and output_file_windows.cpp, of
// which CMake compiles the one of the platform built for.
#pragma once

#include <filesystem>
#include <string>

namespace rt {

// A short hidden name in the target's folder: short, so that it fits the folder's name
// limit whatever the target's length (a 255-byte target name is legal); in the same
// folder, so that the final rename stays on one file system; and one no other run picks
// at the same time: 64 bits mixed (splitmix64's finaliser) from the clock's nanoseconds
// and addresses that address-space randomisation makes differ between processes.
// WHY not std::random_device: the device instruction traps in this virtual machine.
std::filesystem::path temporary_name_in(const std::filesystem::path& folder);

// The folder a target lies in: "." for a bare name.
std::filesystem::path folder_of(const std::filesystem::path& target);

// Why a file could not be created in folder, as precisely as the file system tells.
std::string cannot_create(const std::string& name, const std::filesystem::path& folder, int error);

}  // namespace rt
