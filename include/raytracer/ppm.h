// Binary (P6) and text (P3) PPM files. The save functions keep the handout's template
// signatures (width, height, file name, pixels: width*height*3 bytes, top row first),
// but report failure instead of printing it, and never leave a partial file: they
// write a temporary file beside the target and rename it into place when complete.
#pragma once

#include <string>

#include "raytracer/image.h"

namespace rt {

// Each returns an empty string on success, else what went wrong (for a message).
std::string save_imageP6(int width, int height, const char* file_name, const unsigned char* pixels);
std::string save_imageP3(int width, int height, const char* file_name, const unsigned char* pixels);

// Checks, before a long render, that save_imageP6 will be able to create file_name:
// creates and removes a temporary file beside it. Same return convention.
std::string check_writable(const char* file_name);

// Reads a binary P6 file with maxval 255 (comments allowed in the header). Returns
// false and says why in error when the file cannot be read or is not such a file.
bool read_ppm(const std::string& file_name, Image& image, std::string& error);

}  // namespace rt
