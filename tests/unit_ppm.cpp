// The PPM writers and reader: exact bytes, and no partial or clobbered files.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#ifdef _WIN32
#include <io.h>  // _wunlink
#include "raytracer/windows_api.h"
#else
#include <sys/stat.h>  // mkfifo
#endif

#include "check.h"
#include "image_diff.h"
#include "raytracer/image.h"
#include "raytracer/output_file.h"
#include "raytracer/ppm.h"

namespace fs = std::filesystem;

namespace {

// A fresh, empty folder of its own for each test.
struct ScratchFolder {
    fs::path path;
    ScratchFolder() {
        std::random_device random;
        path = fs::temp_directory_path() /
               ("raytracer-unit-ppm-" + std::to_string(random()) + std::to_string(random()));
        fs::create_directories(path);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    std::string file(const char* name) const { return (path / name).string(); }
    std::size_t entries() const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(path), fs::directory_iterator()));
    }
};

std::string contents(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// 2 x 2 pixels: red, green / blue, white, top row first.
const unsigned char kPixels[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};

}  // namespace

TEST(p6_is_header_then_rows_from_the_top) {
    ScratchFolder dir;
    CHECK_EQ(rt::save_imageP6(2, 2, dir.file("a.ppm").c_str(), kPixels), std::string());
    const std::string expected =
        std::string("P6\n2 2\n255\n") + std::string(reinterpret_cast<const char*>(kPixels), 12);
    CHECK(contents(dir.file("a.ppm")) == expected);
    CHECK_EQ(dir.entries(), 1U);  // no temporary file left behind
}

TEST(p3_is_the_same_image_as_text) {
    ScratchFolder dir;
    CHECK_EQ(rt::save_imageP3(2, 2, dir.file("a.ppm").c_str(), kPixels), std::string());
    CHECK_EQ(contents(dir.file("a.ppm")),
             std::string("P3\n2 2\n255\n 255 0 0 0 255 0\n 0 0 255 255 255 255\n"));
}

TEST(an_existing_image_is_replaced_whole) {
    ScratchFolder dir;
    {
        std::ofstream old(dir.file("a.ppm"), std::ios::binary);
        old << std::string(5000, 'x');
    }
    CHECK_EQ(rt::save_imageP6(2, 2, dir.file("a.ppm").c_str(), kPixels), std::string());
    CHECK_EQ(contents(dir.file("a.ppm")).size(), 11U + 12U);
    CHECK_EQ(dir.entries(), 1U);
}

TEST(an_unwritable_path_fails_and_leaves_nothing) {
    ScratchFolder dir;
    const std::string error = rt::save_imageP6(2, 2, dir.file("missing/a.ppm").c_str(), kPixels);
    CHECK(error.find("cannot be created") != std::string::npos);
    CHECK_EQ(dir.entries(), 0U);
    // A folder in the way of the target: the write fails and the folder survives.
    fs::create_directories(dir.path / "taken.ppm");
    CHECK(!rt::save_imageP6(2, 2, dir.file("taken.ppm").c_str(), kPixels).empty());
    CHECK(fs::is_directory(dir.path / "taken.ppm"));
    CHECK_EQ(dir.entries(), 1U);
}

// The file main.cpp creates before the render: the temporary exists while pending, the
// target appears only at commit, and a file never committed (an error or an exception
// during the render) leaves nothing, not even the temporary, and no old image harmed.
TEST(a_pending_file_appears_only_when_committed) {
    ScratchFolder dir;
    {
        std::ofstream old(dir.file("a.ppm"), std::ios::binary);
        old << "old";
    }
    {
        rt::PendingFile file(dir.file("a.ppm").c_str());
        CHECK_EQ(file.error(), std::string());
#ifdef __linux__
        CHECK_EQ(dir.entries(), 1U);  // the old image only: the new file has no name yet (O_TMPFILE)
#else
        CHECK_EQ(dir.entries(), 2U);  // the old image and the temporary
#endif
        file.write("abc", 3);
    }  // not committed
    CHECK_EQ(dir.entries(), 1U);
    CHECK_EQ(contents(dir.file("a.ppm")), std::string("old"));
    {
        rt::PendingFile file(dir.file("a.ppm").c_str());
        CHECK_EQ(rt::save_imageP6(file, 2, 2, kPixels), std::string());
        CHECK(!file.commit().empty());  // only once
    }
    CHECK_EQ(contents(dir.file("a.ppm")).size(), 11U + 12U);
    CHECK_EQ(dir.entries(), 1U);
    rt::PendingFile unwritable(dir.file("missing/a.ppm").c_str());
    CHECK(unwritable.error().find("cannot be created") != std::string::npos);
    CHECK(!rt::save_imageP6(unwritable, 2, 2, kPixels).empty());
    CHECK_EQ(dir.entries(), 1U);
}

#ifdef _WIN32
// An interrupt's handler removes the temporary while the render still holds it open (the
// console's handler runs on a thread of its own, interrupts.cpp), for file systems that
// refuse to delete it on close (output_file_windows.cpp): Windows allows that only to a
// file opened to share deletion. Opening it for deletion, as _wunlink does first, tells
// the two cases apart: refused as a sharing violation without that share, refused as
// access denied where the file is already being deleted (Windows), allowed where the
// system still lets it be removed (Wine), which the test then does. Gone once closed
// either way, the old image untouched.
TEST(the_temporary_can_be_removed_while_open) {
    ScratchFolder dir;
    {
        std::ofstream old(dir.file("a.ppm"), std::ios::binary);
        old << "old";
    }
    {
        rt::PendingFile file(dir.file("a.ppm").c_str());
        file.write("abc", 3);
        int removable = 0;
        for (const fs::directory_entry& entry : fs::directory_iterator(dir.path)) {
            if (entry.path().filename() == "a.ppm") continue;
            const HANDLE handle = CreateFileW(entry.path().c_str(), DELETE,
                                              FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                                              OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
            if (handle == INVALID_HANDLE_VALUE) {
                removable += GetLastError() == ERROR_ACCESS_DENIED ? 1 : 0;
            } else {
                (void)CloseHandle(handle);
                removable += _wunlink(entry.path().c_str()) == 0 ? 1 : 0;
            }
        }
        CHECK_EQ(removable, 1);
    }
    CHECK_EQ(dir.entries(), 1U);
    CHECK_EQ(contents(dir.file("a.ppm")), std::string("old"));
}
#endif

TEST(read_ppm_reads_what_save_wrote) {
    ScratchFolder dir;
    CHECK_EQ(rt::save_imageP6(2, 2, dir.file("a.ppm").c_str(), kPixels), std::string());
    rt::Image image;
    std::string error;
    CHECK(rt::read_ppm(dir.file("a.ppm"), image, error));
    CHECK_EQ(image.width, 2);
    CHECK_EQ(image.height, 2);
    CHECK(image.rgb.size() == 12 && std::equal(image.rgb.begin(), image.rgb.end(), kPixels));
}

TEST(read_ppm_refuses_what_is_not_a_p6_image) {
    ScratchFolder dir;
    rt::Image image;
    std::string error;
    CHECK(!rt::read_ppm(dir.file("none.ppm"), image, error));
    CHECK_EQ(rt::save_imageP3(2, 2, dir.file("p3.ppm").c_str(), kPixels), std::string());
    CHECK(!rt::read_ppm(dir.file("p3.ppm"), image, error));
    {
        std::ofstream shortfile(dir.file("short.ppm"), std::ios::binary);
        shortfile << "P6\n2 2\n255\nabc";
    }
    CHECK(!rt::read_ppm(dir.file("short.ppm"), image, error));
    CHECK(error.find("shorter") != std::string::npos);
}

// Each refusal says what is wrong: the system's reason, a folder, a size beyond 2^31
// pixels (found from the header alone, before any memory is taken for the pixels).
TEST(read_ppm_says_why_it_refuses) {
    ScratchFolder dir;
    rt::Image image;
    std::string error;
    CHECK(!rt::read_ppm(dir.file("none.ppm"), image, error));
    CHECK(error.find("cannot open '") != std::string::npos && error.find("': ") != std::string::npos);
    CHECK(!rt::read_ppm(dir.file(""), image, error));
    CHECK(error.find("is a folder") != std::string::npos);
    {
        std::ofstream huge(dir.file("huge.ppm"), std::ios::binary);
        huge << "P6\n70000 40000\n255\n";
    }
    CHECK(!rt::read_ppm(dir.file("huge.ppm"), image, error));
    CHECK(error.find("70000x40000 pixels, more than the 2^31") != std::string::npos);
    int width = 0, height = 0;
    error.clear();
    CHECK(rt::read_ppm_size(dir.file("huge.ppm"), width, height, error) == false);
    {
        std::ofstream big(dir.file("big.ppm"), std::ios::binary);
        big << "P6\n30000 30000\n255\n";
    }
    CHECK(rt::read_ppm_size(dir.file("big.ppm"), width, height, error));
    CHECK_EQ(width, 30000);
    CHECK_EQ(height, 30000);
}

// Netpbm's header and nothing looser: a header a PPM reader refuses is refused, not
// read for the numbers it starts with; comments and any whitespace between fields pass.
TEST(read_ppm_takes_only_a_well_formed_header) {
    ScratchFolder dir;
    const std::string pixels(12, 'A');
    auto reads = [&dir](const std::string& bytes) {
        std::ofstream(dir.file("h.ppm"), std::ios::binary) << bytes;
        rt::Image image;
        std::string error;
        const bool read = rt::read_ppm(dir.file("h.ppm"), image, error);
        CHECK(read == error.empty());
        CHECK(read || error.find("is not a binary PPM (P6) with maxval 255") != std::string::npos ||
              error.find("pixels, expected at least one") != std::string::npos);
        return read && image.width == 2 && image.height == 2;
    };
    CHECK(reads("P6\n2 2\n255\n" + pixels));
    CHECK(reads("P6 2\t2\r\n255\n" + pixels));
    CHECK(reads("P6#a comment\n2#another\n  2 \n# and one more\n255\n" + pixels));
    CHECK(reads("P6\n02 2\n0255\n" + pixels));
    CHECK(!reads("\nP6\n2 2\n255\n" + pixels));  // the magic number first
    CHECK(!reads(" P6\n2 2\n255\n" + pixels));
    CHECK(!reads("P62 2\n255\n" + pixels));
    CHECK(!reads("P6\n2abc 2\n255\n" + pixels));
    CHECK(!reads("P6\n2 2junk\n255\n" + pixels));
    CHECK(!reads("P6\n2 2.9\n255\n" + pixels));
    CHECK(!reads("P6\n2 +2\n255\n" + pixels));
    CHECK(!reads("P6\n2 -2\n255\n" + pixels));
    CHECK(!reads("P6\n2 2\n255#\n" + pixels));  // one whitespace byte before the pixels
    CHECK(!reads("P6\n2 2\n65535\n" + pixels + pixels));
    CHECK(!reads("P6\n0 2\n255\n"));
    CHECK(!reads("P6\n2 2\n255"));
}

// An image of no pixels is named so (a grader reports it), not "not a binary PPM"; a FIFO
// is refused before it is opened, which would wait for a writer for good.
TEST(read_ppm_names_an_empty_image_and_refuses_what_is_not_a_file) {
    ScratchFolder dir;
    std::ofstream(dir.file("empty.ppm"), std::ios::binary) << "P6\n0 0\n255\n";
    rt::Image image;
    std::string error;
    CHECK(!rt::read_ppm(dir.file("empty.ppm"), image, error));
    CHECK(error.find("is a P6 of 0x0 pixels, expected at least one") != std::string::npos);
#ifndef _WIN32
    CHECK_EQ(::mkfifo(dir.file("fifo.ppm").c_str(), 0600), 0);
    error.clear();
    CHECK(!rt::read_ppm(dir.file("fifo.ppm"), image, error));
    CHECK(error.find("is not a regular file") != std::string::npos);
#endif
}

// A header claiming more than the file holds: refused as short, with no more memory
// than the file's; past 2^31 - 1 pixels (2^31 itself would not fit an int) from the header.
TEST(read_ppm_trusts_no_header_with_memory) {
    ScratchFolder dir;
    rt::Image image;
    std::string error;
    std::ofstream(dir.file("claims.ppm"), std::ios::binary) << "P6\n46000 46000\n255\n"
                                                            << std::string(100, 'A');
    CHECK(!rt::read_ppm(dir.file("claims.ppm"), image, error));  // 6.3 GB claimed
    CHECK(error.find("is shorter than its header says") != std::string::npos);
    CHECK(image.rgb.capacity() <= std::size_t{1} << 20);
    for (const char* header :
         {"P6\n2147483648 1\n255\n", "P6\n65536 32768\n255\n", "P6\n1 99999999999999999999\n255\n"}) {
        std::ofstream(dir.file("big.ppm"), std::ios::binary) << header;
        error.clear();
        CHECK(!rt::read_ppm(dir.file("big.ppm"), image, error));
        CHECK(error.find("pixels, more than the 2^31 - 1 read") != std::string::npos);
    }
}

TEST(read_ppm_counts_the_bytes_after_the_pixels) {
    ScratchFolder dir;
    CHECK_EQ(rt::save_imageP6(2, 2, dir.file("a.ppm").c_str(), kPixels), std::string());
    rt::Image image;
    std::string error;
    std::uint64_t after = 99;
    CHECK(rt::read_ppm(dir.file("a.ppm"), image, error, &after));
    CHECK_EQ(after, std::uint64_t{0});
    std::ofstream(dir.file("a.ppm"), std::ios::binary | std::ios::app) << "junk";
    CHECK(rt::read_ppm(dir.file("a.ppm"), image, error, &after));
    CHECK_EQ(after, std::uint64_t{4});
}

TEST(compare_counts_pixels_and_the_largest_difference) {
    const rt::Image a{2, 1, {10, 20, 30, 40, 50, 60}};
    rt::Image b{2, 1, {10, 20, 30, 40, 50, 60}};
    CHECK_EQ(compare_images(a, b).differing_pixels, 0);
    b.rgb[1] = 23;  // pixel 0, green, 3 levels
    b.rgb[5] = 59;  // pixel 1, blue, 1 level
    const ImageDiff d = compare_images(a, b);
    CHECK(d.same_size);
    CHECK_EQ(d.differing_pixels, 2);
    CHECK_EQ(d.largest_difference, 3);
    CHECK(!compare_images(a, rt::Image{1, 2, {10, 20, 30, 40, 50, 60}}).same_size);
}

// P6Writer: the header at once, rows as they come; an image whose rows did not all come
// is not committed, and no file is left.
TEST(p6_writer_writes_rows_as_they_come) {
    ScratchFolder dir;
    {
        rt::PendingFile file(dir.file("a.ppm").c_str());
        rt::P6Writer writer(file, 2, 2);
        writer.write_rows(kPixels, 6);
        writer.write_rows(kPixels + 6, 6);
        CHECK_EQ(writer.commit(), std::string());
    }
    rt::Image image;
    std::string error;
    CHECK(rt::read_ppm(dir.file("a.ppm"), image, error));
    CHECK(image.rgb.size() == 12 && std::equal(image.rgb.begin(), image.rgb.end(), kPixels));
    {
        rt::PendingFile file(dir.file("b.ppm").c_str());
        rt::P6Writer writer(file, 2, 2);
        writer.write_rows(kPixels, 6);
        CHECK(!writer.commit().empty());
    }
    CHECK(!fs::exists(dir.file("b.ppm")));
    CHECK_EQ(dir.entries(), std::size_t{1});  // a.ppm only: no temporary left
}
