// floor <file>: starts, writes a 400x400 binary PPM (P6) in one write, and exits. The
// fixed cost that any renderer of a 400x400 image pays (process start-up, page-ins,
// the write): the yardstick of the benchmark's target (a). Linked like raytracer.exe.
#include <cstdio>
#include <cstring>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    const char header[] = "P6\n400 400\n255\n";
    const std::size_t header_size = sizeof header - 1, pixels = std::size_t{400} * 400 * 3;
    std::vector<unsigned char> file(header_size + pixels, 127);
    std::memcpy(file.data(), header, header_size);
    std::FILE* out = std::fopen(argv[1], "wb");
    if (out == nullptr) return 1;
    const bool written = std::fwrite(file.data(), 1, file.size(), out) == file.size();
    return std::fclose(out) == 0 && written ? 0 : 1;
}
