// Text from outside as messages show it (shown.h): escaped and cut for one-line
// messages, and only the control characters escaped for the grader's report lines.
#include <string>

#include "check.h"
#include "raytracer/shown.h"

TEST(shown_quotes_escapes_and_cuts) {
    CHECK_EQ(rt::shown("out.ppm"), std::string("'out.ppm'"));
    CHECK_EQ(rt::shown("a\x1b[2Jb"), std::string("'a\\x1b[2Jb'"));
    CHECK_EQ(rt::shown("caf\xc3\xa9"), std::string("'caf\\xc3\\xa9'"));
    CHECK_EQ(rt::shown("a\\x1b"), std::string("'a\\x5cx1b'"));  // the text \x1b, not an ESC byte
    CHECK_EQ(rt::shown("C:\\scenes"), std::string("'C:\\scenes'"));
    CHECK_EQ(rt::shown(std::string(50, 'x'), 4), std::string("'xxxx...' (50 bytes)"));
    CHECK_EQ(rt::escaped(std::string(50, 'x'), 4), std::string("xxxx... (50 bytes)"));
}

TEST(controls_escaped_leaves_everything_but_control_characters) {
    // C0 controls and DEL.
    CHECK_EQ(rt::controls_escaped("test\x1b[2J\x1b]0;owned\x07X"),
             std::string("test\\x1b[2J\\x1b]0;owned\\x07X"));
    CHECK_EQ(rt::controls_escaped(std::string("a\0b\x7f", 4)), std::string("a\\x00b\\x7f"));
    CHECK_EQ(rt::controls_escaped("line\nnext\r"), std::string("line\\x0anext\\x0d"));
    // C1 controls as UTF-8 writes them (U+009B, the one-byte CSI, is C2 9B).
    CHECK_EQ(rt::controls_escaped("a\xc2\x9b"
                                  "2Jb"),
             std::string("a\\xc2\\x9b2Jb"));
    // Other UTF-8 (U+00E9, U+00A0 after C2) and backslashes as they are.
    CHECK_EQ(rt::controls_escaped("caf\xc3\xa9 \xc2\xa0"), std::string("caf\xc3\xa9 \xc2\xa0"));
    CHECK_EQ(rt::controls_escaped("exited: \\x1b[31m"), std::string("exited: \\x1b[31m"));
    CHECK_EQ(rt::controls_escaped("\xc2"), std::string("\xc2"));  // a lone lead byte at the end
}
