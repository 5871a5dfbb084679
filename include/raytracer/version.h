#pragma once

namespace rt {
inline constexpr const char* kVersion = "1.0.0";
}
