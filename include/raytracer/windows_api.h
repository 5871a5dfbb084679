// <windows.h> without its min and max macros, which would break std::min and std::max
// in every file that includes it after them (the core compiles as one unit). Windows only.
#pragma once

#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>
