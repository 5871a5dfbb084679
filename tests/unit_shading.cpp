#include "check.h"
TEST(placeholder) { CHECK(true); }
