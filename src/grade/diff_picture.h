// The picture of a failing scene: key | yours | difference, side by side, for a student to
// see where the images differ. In the difference panel the key is shown dimmed, a pixel
// off by one level dark blue, a known ambiguous pixel showing the other outcome (allowed)
// yellow, and an unexplained one red, brighter the larger the difference; when there are
// few, each is also ringed (over no other pixel's mark) so that a single pixel stands out.
#pragma once

#include <string>

#include "raytracer/image.h"

namespace grade {

// key and got have the same size; an empty picture where three panels would be wider
// than an int.
rt::Image difference_picture(const std::string& key_name, const rt::Image& key, const rt::Image& got);

}  // namespace grade
