// The image's file while it is written: created before the render, so that an
// unwritable target is known before the render is spent on it, and put in place only
// when complete, so that no failure or interruption leaves a partial image or touches an
// existing one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rt {

// The hidden temporary an image is written to before it is put in place: the prefix, 16
// hex digits and the suffix (temporary_name_in(), output_file.cpp); choose_output() asks
// the system about a name of its length in the image's folder.
inline constexpr std::string_view kTemporaryPrefix = ".raytracer-", kTemporarySuffix = ".tmp";
inline constexpr std::size_t kTemporaryNameBytes = kTemporaryPrefix.size() + 16 + kTemporarySuffix.size();

// Where the bytes go.
enum class Destination {
    // A new file, or a regular file replaced whole (keeping its permissions) once
    // complete. On Linux the file is created unnamed (O_TMPFILE) and linked into place
    // by commit(), so even SIGKILL leaves nothing (but between the two system calls
    // that replace an existing file: link_unnamed()); on Windows it is a hidden temporary
    // beside the target that the system deletes when the process ends, however it ends,
    // until commit() keeps it; elsewhere such a temporary, removed on error and by the
    // interrupt handlers (interrupts.h).
    Replace,
    // An existing device or FIFO, written directly (the user named it with -o).
    WriteInto,
    // Standard output (-o -).
    StandardOutput,
    // A descriptor this process was started with, other than the standard streams
    // (-o /dev/fd/3 with 3> f.ppm): written into as it is open, at its offset, as
    // standard output is.
    Descriptor,
};

// A path in the system's encoding, std::filesystem::path::string_type (UTF-16 on
// Windows), named without <filesystem>, whose header costs each file that includes this
// one 0.5 s to build (output_file.cpp checks that the two are the same type).
#ifdef _WIN32
using NativePath = std::wstring;
#else
using NativePath = std::string;
#endif

class PendingFile {
public:
    // within_working_folder: the file's folder must lie in the working folder or below it
    // (a scene's OUTPUT, folder_place.h). On POSIX systems the folder is held open from
    // that check on, and the file is created, linked and renamed in it by descriptor, so
    // a folder on the way replaced meanwhile (by a link out) cannot move the image.
    // descriptor: the one Destination::Descriptor writes into.
    explicit PendingFile(const char* file_name, Destination destination = Destination::Replace,
                         bool within_working_folder = false, int descriptor = -1);
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;
    ~PendingFile();

    // Why the file could not be created; empty when it was.
    const std::string& error() const { return error_; }
    // Announces the final size, so that the file system allocates it at once (a hint,
    // ignored where unsupported: see output_file_posix.cpp for why it pays), and so that a
    // stream knows when the whole image is out.
    void expect_size(std::uint64_t bytes);
    // Appends the bytes (only when error() is empty); a failure is reported by commit().
    // (write() and expect_size() are the platform's: output_file_posix.cpp, _windows.cpp.)
    void write(const void* data, std::size_t size);
    // Whether a write has failed: no later byte is written, and commit() says why.
    bool write_failed() const { return write_error_ != 0; }
    // Puts the complete file in place. Returns an empty string on success, else what
    // went wrong; nothing is left behind either way.
    std::string commit();

private:
    void open_replacement();
    bool open_unnamed(const NativePath& folder);
    void open_named(const NativePath& folder);
    void remove_temporary();
#ifndef _WIN32
    bool replace_target(std::string& error);
#endif
    bool link_unnamed(std::string& error);
    void discard();
    void close_file();
    // Closes the complete named temporary and renames it over the target; on failure,
    // why (with the name), and discard() removes what is left.
    std::string put_in_place();
    std::string write_failure() const;
    void stream_bytes_ahead() const;
    void stream_bytes_out(std::size_t size);

    std::string name_;  // as given, for messages
    Destination destination_;
    bool within_working_folder_;
    // The target and the temporary; on POSIX systems their names in folder_ (temporary_
    // empty while unnamed).
    NativePath target_, temporary_;
#ifdef _WIN32
    std::FILE* file_ = nullptr;
    bool deleted_on_close_ = false;  // the temporary goes when its handle closes
#else
    int fd_ = -1;
    int folder_ = -1;  // the target's folder, held open (open_folder()), or AT_FDCWD
#endif
    bool open_ = false;                         // the file is ours to write
    bool unnamed_ = false;                      // created with O_TMPFILE: no name until commit()
    bool replaces_ = false;                     // the target existed: it is replaced, not created
    std::uint64_t expected_ = 0, written_ = 0;  // bytes: expect_size(), and to a stream so far
    unsigned keep_mode_ = 0;
    int write_error_ = 0;  // errno of the first failed write; 0: none
    std::string error_;
};

// The bytes as the whole file file_name, put in place when complete (Destination::Replace).
// Returns an empty string on success, else what went wrong, with the name.
std::string write_whole_file(const char* file_name, const void* data, std::size_t size);

}  // namespace rt
