// Text from outside (tokens, file names, paths) as it may appear in a one-line message:
// control and non-ASCII bytes escaped as \xNN, so that a scene cannot reach the terminal
// with escape sequences, and long values cut, so that a 1 MB name still gives one short
// line; and counts with their nouns.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rt {

// Tokens are cut at this many bytes, paths at the longer kMaxShownPath.
inline constexpr std::size_t kMaxShownToken = 40;
inline constexpr std::size_t kMaxShownPath = 160;

// Escaped and cut, without quotes: the text, or "first bytes... (N bytes)". A byte
// outside printable ASCII shows as \xNN (so a cut may fall inside a UTF-8 character),
// and so does a backslash before an x, as \x5c: every \x shown starts an escape, so a
// name written "\x1b" and one holding an ESC byte read apart, while other backslashes,
// as in Windows paths, show as they are.
std::string escaped(std::string_view text, std::size_t most = kMaxShownPath);

// Quoted, escaped and cut: 'text', or 'first bytes...' (N bytes).
std::string shown(std::string_view text, std::size_t most = kMaxShownToken);

// The control characters alone escaped as \xNN (C0, DEL, and C1 as UTF-8 writes them),
// the rest as it is: for whole lines of text that hold names already shown (the
// grader's report), where other UTF-8 stays readable and no escape sequence gets through.
std::string controls_escaped(std::string_view text);

// A count and its noun: "1 light", "2 lights" (plural(n, "light", "lights")).
std::string plural(long long count, const char* one, const char* many);

}  // namespace rt
