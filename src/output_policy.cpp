#include "raytracer/output_policy.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "raytracer/folder_place.h"
#include "raytracer/output_file.h"
#include "raytracer/parser.h"
#include "raytracer/shown.h"
#include "raytracer/standard_streams.h"

#ifdef _WIN32
#include "raytracer/windows_api.h"
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace rt {
namespace {

namespace fs = std::filesystem;

// What is at a path now, as far as choosing how to write it goes: Pipe is a FIFO or a
// socket, Other a device or anything else that is not a regular file.
enum class Existing { Nothing, RegularFile, Folder, Pipe, Other };

#ifdef _WIN32
// The names of a path after its root ("C:\\"); none for a path that is not UTF-8
// (PendingFile says so).
std::vector<fs::path> names_of(const std::string& path) {
    std::vector<fs::path> names;
    try {
        for (const fs::path& part : fs::u8path(path).relative_path()) names.push_back(part);
    } catch (const std::exception&) {
        names.clear();
    }
    return names;
}

// Whether a name of the path is longer than a Windows folder allows (255 UTF-16 units).
bool name_too_long(const std::string& path) {
    for (const fs::path& name : names_of(path))
        if (name.native().size() > 255) return true;
    return false;
}

// Why Windows would refuse the path's names, or empty: characters it does not allow in a
// name (a ':' past the drive would name a stream of another file). Said before the
// render, not when the image is put there. A path in Windows' own namespaces (\\?\C:\...,
// \\.\NUL: -o only) is the system's to judge.
std::string unusable_name(const std::string& path) {
    if (path.rfind("\\\\?\\", 0) == 0 || path.rfind("\\\\.\\", 0) == 0) return {};
    for (const fs::path& name : names_of(path))
        for (const char c : name.u8string())
            if (static_cast<unsigned char>(c) < 0x20 || std::strchr("<>:\"|?*", c) != nullptr)
                return " holds a character that Windows does not allow in a file name (< > : \" | ? * or a "
                       "control character), expected another name";
    return {};
}

// Whether the path's last name is one that Windows keeps for a device in every folder:
// CON, PRN, AUX, NUL, COM0-COM9 and LPT0-LPT9 (and with a superscript 1, 2 or 3),
// CONIN$ and CONOUT$, also before an extension ("Naming Files, Paths, and Namespaces",
// Microsoft Learn). fs::status finds nothing there, and a rename would put the image
// in the device's place.
bool device_name(const std::string& path) {
    const std::vector<fs::path> names = names_of(path);
    if (names.empty()) return false;
    const std::string last = names.back().u8string();
    std::string name = last.substr(0, last.find('.'));
    while (!name.empty() && name.back() == ' ') name.pop_back();
    for (char& c : name) c = c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    for (const char* device : {"CON", "PRN", "AUX", "NUL", "CONIN$", "CONOUT$"})
        if (name == device) return true;
    if (name.rfind("COM", 0) != 0 && name.rfind("LPT", 0) != 0) return false;
    const std::string number = name.substr(3);
    return (number.size() == 1 && number[0] >= '0' && number[0] <= '9') || number == "\xC2\xB9" ||
           number == "\xC2\xB2" || number == "\xC2\xB3";
}

// Why this user may not replace the file at path, or empty: it is read-only.
std::string unreplaceable(const std::string& path) {
    const DWORD attributes = GetFileAttributesW(fs::u8path(path).c_str());
    if (attributes != INVALID_FILE_ATTRIBUTES && (attributes & FILE_ATTRIBUTE_READONLY) != 0)
        return " is write-protected (read-only), expected a file it may write";
    return {};
}

Existing what_is_at(const std::string& path) {
    if (device_name(path)) return Existing::Other;
    std::error_code ec;
    const fs::file_status status = fs::status(fs::u8path(path), ec);
    if (ec || status.type() == fs::file_type::not_found) return Existing::Nothing;
    if (status.type() == fs::file_type::directory) return Existing::Folder;
    if (status.type() == fs::file_type::fifo || status.type() == fs::file_type::socket) return Existing::Pipe;
    return status.type() == fs::file_type::regular ? Existing::RegularFile : Existing::Other;
}
#else
// Whether the system refuses the path as too long (a name past its folder's limit, or a
// path past the system's): said before the render, not when the image is put there.
// The temporary's name in the same folder is asked too (a name of its length): the image
// goes there before it replaces an existing file (and always where there is no O_TMPFILE).
bool name_too_long(const std::string& path) {
    const fs::path folder = fs::path(path).parent_path();
    const std::string temporary = (folder / std::string(kTemporaryNameBytes, 'x')).string();
    struct stat s {};
    for (const std::string& name : {path, temporary})
        if (::stat(name.c_str(), &s) != 0 && errno == ENAMETOOLONG) return true;
    return false;
}

// Any byte but '/' and NUL may be in a name here.
std::string unusable_name(const std::string& /*path*/) { return {}; }

// Whether this process may replace another user's file in a sticky folder: CAP_FOWNER
// (on Linux its effective capabilities, which root in a container may lack), else root.
bool overrides_sticky_folders() {
#ifdef __linux__
    if (std::FILE* status = std::fopen("/proc/self/status", "r")) {
        char line[256];
        unsigned long long effective = 0;
        bool found = false;
        while (!found && std::fgets(line, sizeof line, status) != nullptr)
            found = std::sscanf(line, "CapEff: %llx", &effective) == 1;
        std::fclose(status);
        if (found) return (effective >> 3 & 1U) != 0;  // CAP_FOWNER is capability 3
    }
#endif
    return ::geteuid() == 0;
}

// Why this user may not replace the regular file at path, or empty: it is write-protected
// (a policy: a shell's > and cp refuse it too), in a folder this user may not write
// (the complete image is renamed over it there), or another user's in a folder with the
// sticky bit (/tmp), where rename() may not replace it. A symbolic link at the name is
// what is replaced (not followed): its own owner counts, not its target's permissions.
std::string unreplaceable(const std::string& path) {
    struct stat name {
    }, folder{};
    if (::lstat(path.c_str(), &name) != 0) return {};
    if (!S_ISLNK(name.st_mode) && ::faccessat(AT_FDCWD, path.c_str(), W_OK, AT_EACCESS) != 0 &&
        errno == EACCES)
        return " is write-protected (no write permission for this user), expected a file it may write";
    const fs::path parent = fs::path(path).parent_path();
    const char* const parent_name = parent.empty() ? "." : parent.c_str();
    if (::faccessat(AT_FDCWD, parent_name, W_OK, AT_EACCESS) != 0 && errno == EACCES)
        return " is in a folder this user may not write, where the complete image would be renamed over it, "
               "expected a file in a writable folder";
    const uid_t user = ::geteuid();
    if (::stat(parent_name, &folder) == 0 && (folder.st_mode & S_ISVTX) != 0 && name.st_uid != user &&
        folder.st_uid != user && !overrides_sticky_folders())
        return " is another user's file in a folder where only its owner may replace it (sticky, as /tmp), "
               "expected a file of this user";
    return {};
}

Existing what_is_at(const std::string& path) {
    struct stat s {};
    if (::stat(path.c_str(), &s) != 0) return Existing::Nothing;
    if (S_ISDIR(s.st_mode)) return Existing::Folder;
    if (S_ISFIFO(s.st_mode) || S_ISSOCK(s.st_mode)) return Existing::Pipe;
    return S_ISREG(s.st_mode) ? Existing::RegularFile : Existing::Other;
}
#endif

// Why a scene may not name this path, or empty: only names relative to the working
// folder that stay in it or below.
std::string outside_working_folder(const std::string& output) {
    const std::string elsewhere = " (-o PATH on the command line writes anywhere)";
    fs::path path;
    try {
        path = fs::u8path(output);
    } catch (const std::exception&) {
        return shown(output, kMaxShownPath) + " is not a usable file name, expected a file name";
    }
    if (path.has_root_name() && !path.has_root_directory())  // C:out.ppm, on Windows
        return shown(output, kMaxShownPath) +
               " names a drive, expected a file name in or below the working folder" + elsewhere;
    if (path.has_root_directory())  // the absolute paths: /x, C:\x, \\server\share
        return shown(output, kMaxShownPath) +
               " is an absolute path, expected a file name in or below the working folder" + elsewhere;
    for (const fs::path& part : path)
        if (part == "..")
            return shown(output, kMaxShownPath) +
                   " leaves the working folder ('..'), expected a file name in or below it" + elsewhere;
    // A folder on the way may be a symbolic link out of the working folder. Asked of the
    // file system only for names with a folder (a bare file name costs nothing).
    if (!path.has_parent_path()) return {};
    int error = 0;
    switch (place_of(path.parent_path().native(), error)) {
        case FolderPlace::Inside:
        case FolderPlace::Missing:
            return {};
        case FolderPlace::Outside:
            return shown(output, kMaxShownPath) +
                   " leaves the working folder through a symbolic link, expected a file name in or below it" +
                   elsewhere;
        case FolderPlace::Unknown:
            break;
    }
    return shown(output, kMaxShownPath) + " cannot be checked to stay in the working folder (" +
           std::system_category().message(error) + "), expected a file name in or below it" + elsewhere;
}

// The descriptor N that path names as /dev/fd/N or /proc/self/fd/N (Linux: its folder,
// links followed, is /proc/self/fd's), N > 2, whether open or not; else -1.
// Such a path is a link that /proc makes, which no file can replace.
int descriptor_named(const std::string& path) {
#ifdef __linux__
    const fs::path named(path);
    const std::string name = named.filename().string();
    if (name.empty() || name.size() > 9 || name.find_first_not_of("0123456789") != std::string::npos)
        return -1;
    const int descriptor = std::stoi(name);
    std::error_code ec;
    // /proc/self/fd as this process's /proc shows it (its own PID namespace's numbers).
    const fs::path folder = fs::canonical(named.has_parent_path() ? named.parent_path() : ".", ec);
    if (ec || folder != fs::canonical("/proc/self/fd", ec) || ec || std::to_string(descriptor) != name ||
        descriptor <= 2)
        return -1;
    return descriptor;
#else
    (void)path;
    return -1;
#endif
}

// Why descriptor N, named as path, cannot take the image, or empty.
std::string unwritable_descriptor(const std::string& path, int descriptor) {
#ifdef _WIN32
    (void)path, (void)descriptor;
    return {};
#else
    const std::string n = std::to_string(descriptor);
    const std::string is = shown(path, kMaxShownPath) + " is descriptor " + n + ", which is ";
    const std::string for_writing = ", expected one open for writing (" + n + "> file)";
    const int flags = ::fcntl(descriptor, F_GETFL);
    if (flags < 0) return is + "not open" + for_writing;
    if ((flags & O_ACCMODE) == O_RDONLY) return is + "open for reading only" + for_writing;
    if (::isatty(descriptor) != 0)  // as -o - on a terminal
        return is + "a terminal, expected a pipe or a file for a binary image";
    return {};
#endif
}

// Why the path itself, whatever is there, cannot be the image's, or empty: a name the
// system does not allow, one that names a folder, one too long.
std::string unusable_path(const std::string& path) {
    if (const std::string why = unusable_name(path); !why.empty()) return shown(path, kMaxShownPath) + why;
    // "out/" names a folder whether or not there is one: said so, not "'out' does not exist".
    if (!path.empty() &&
        (path.back() == '/' || path.back() == static_cast<char>(fs::path::preferred_separator)))
        return shown(path, kMaxShownPath) +
               " ends in a separator, which names a folder, expected a file name";
    if (name_too_long(path))
        return shown(path, kMaxShownPath) + " is too long a name or path for the system (" +
               std::strerror(ENAMETOOLONG) + "), expected a shorter one";
    return {};
}

// Nor is a regular file that is standard input or error replaced, whoever names it:
// the one is read, the other carries the messages; nor is a pipe that is standard input
// written (this process holds its reading end: a pipe's worth would block it for good).
// A device such as /dev/null is written into as usual. Why not, or empty.
std::string standard_stream_refusal(const std::string& path, Existing existing) {
    for (const auto& [stream, what] :
         {std::pair<int, const char*>{0, "standard input, which is read"},
          std::pair<int, const char*>{2, "standard error, where the messages go"}}) {
        if ((existing == Existing::RegularFile || (stream == 0 && existing == Existing::Pipe)) &&
            standard_stream_is(stream, path))
            return shown(path, kMaxShownPath) + " is " + what + ", expected another file for the image";
    }
    return {};
}

}  // namespace

OutputChoice choose_output(const std::string& scene_output, const std::string* user_output,
                           const std::string& scene_file) {
    // A scene read from standard input ("-") is the regular file standard input is, if any.
    const bool from_standard_input = scene_file == kStandardInput;
    OutputChoice choice;
    choice.named_by_user = user_output != nullptr;
    choice.path = choice.named_by_user ? *user_output : scene_output;
    if (choice.named_by_user && choice.path == "-") {
        choice.destination = Destination::StandardOutput;
        if (standard_stream_is_folder(1))  // raytracer.exe -o - scene.txt >&-
            choice.refusal = "- (standard output) is closed (or a folder), expected a pipe or a file";
        // raytracer.exe -o - scene.txt >> scene.txt
        else if (from_standard_input ? standard_streams_are_one_file(1, 0)
                                     : standard_stream_is(1, scene_file))
            choice.refusal =
                "- (standard output) is the scene file itself, expected another file for the image";
        return choice;
    }
    if (!choice.named_by_user) {
        choice.refusal = outside_working_folder(choice.path);
        if (!choice.refusal.empty()) return choice;
    }
    choice.refusal = unusable_path(choice.path);
    if (!choice.refusal.empty()) return choice;
    const Existing existing = what_is_at(choice.path);
    if (choice.named_by_user && existing == Existing::Folder)
        choice.refusal = closed_stream_named(choice.path);
    if (!choice.refusal.empty()) return choice;
    // -o /dev/fd/N (3> f.ppm, 3>> f.ppm): a link that /proc makes, which cannot be
    // replaced; the descriptor is written into as it is open, as standard output is.
    const int descriptor = choice.named_by_user ? descriptor_named(choice.path) : -1;
    if (descriptor >= 0 && existing == Existing::Nothing) {
        choice.refusal = unwritable_descriptor(choice.path, descriptor);
        return choice;
    }
    if (existing == Existing::Nothing || existing == Existing::Folder)
        return choice;  // a folder: PendingFile says so
    if (from_standard_input ? existing == Existing::RegularFile && standard_stream_is(0, choice.path)
                            : same_file(choice.path, scene_file)) {
        choice.refusal = shown(choice.path, kMaxShownPath) +
                         " is the scene file itself, expected another file for the image";
        return choice;
    }
    // -o /dev/stdout (or /dev/fd/1, or the file standard output goes to): written as
    // standard output, not replaced (that would replace the link, or /dev's own entry).
    if (choice.named_by_user && standard_stream_is(1, choice.path)) {
        choice.destination = Destination::StandardOutput;
        return choice;
    }
    choice.refusal = standard_stream_refusal(choice.path, existing);
    if (!choice.refusal.empty()) return choice;
    if (descriptor >= 0) {
        choice.refusal = unwritable_descriptor(choice.path, descriptor);
        choice.destination = Destination::Descriptor;
        choice.descriptor = descriptor;
        return choice;
    }
    if (existing == Existing::RegularFile) {
        const std::string why = unreplaceable(choice.path);
        if (!why.empty()) choice.refusal = shown(choice.path, kMaxShownPath) + why;
        return choice;
    }
    if (existing == Existing::Pipe || existing == Existing::Other) {
        if (choice.named_by_user) {
            choice.destination = Destination::WriteInto;  // a device or FIFO the user chose
        } else {
            choice.refusal = shown(choice.path, kMaxShownPath) +
                             " is not a regular file (a device, FIFO or socket), expected a regular file "
                             "(-o PATH on the command line writes into it)";
        }
    }
    return choice;
}

}  // namespace rt
