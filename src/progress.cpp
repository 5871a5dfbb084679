#include "raytracer/progress.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "raytracer/interrupts.h"

#ifdef _WIN32
#include <io.h>
#include "raytracer/windows_api.h"
#else
#include <sys/ioctl.h>
#include <unistd.h>
#endif

namespace rt {

namespace {

std::string seconds(double s) {
    char text[32];
    if (s < 60) {
        (void)std::snprintf(text, sizeof text, "%.0f s", s);
    } else {
        const long long whole = static_cast<long long>(std::min(s, 1e15));  // long is 32 bits on Windows
        (void)std::snprintf(text, sizeof text, "%lld:%02lld min", whole / 60, whole % 60);
    }
    return text;
}

// The columns of the terminal stderr shows, or 80 where the system does not say.
int terminal_columns() {
#ifdef _WIN32
    CONSOLE_SCREEN_BUFFER_INFO info{};
    if (GetConsoleScreenBufferInfo(GetStdHandle(STD_ERROR_HANDLE), &info) != 0)
        return info.srWindow.Right - info.srWindow.Left + 1;
#else
    winsize size{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
#endif
    return 80;
}

}  // namespace

bool is_terminal(std::FILE* stream) {
#ifdef _WIN32
    return _isatty(_fileno(stream)) != 0;
#else
    return isatty(fileno(stream)) != 0;
#endif
}

ProgressSink::ProgressSink(RowSink& inner, int total_rows, bool enabled)
    : inner_(inner),
      total_(total_rows),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      next_draw_(start_ + kFirstAfter) {
    // One column short of the width: a line that fills the last column wraps on some
    // terminals.
    if (enabled_) width_ = std::min(terminal_columns() - 1, kMaxErasedLine);
}

void ProgressSink::rows_finished(int count) {
    if (!enabled_) return;
    done_.store(count, std::memory_order_relaxed);
    still_rendering();
}

void ProgressSink::still_rendering() {
    if (!enabled_ || std::this_thread::get_id() != drawer_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_draw_ || done_.load(std::memory_order_relaxed) >= total_) return;
    next_draw_ = now + kRedrawEvery;
    draw(now - start_);
}

void ProgressSink::draw(std::chrono::steady_clock::duration elapsed) {
    const double spent = std::chrono::duration<double>(elapsed).count();
    const double done = done_.load(std::memory_order_relaxed);
    const double fraction = total_ <= 0 ? 1.0 : done / static_cast<double>(total_);
    const double left = fraction > 0 ? spent * (1 - fraction) / fraction : 0;
    char line[96];
    const int length =
        std::snprintf(line, sizeof line, "raytracer.exe: %3d%% of rows, %s elapsed, about %s left",
                      static_cast<int>(fraction * 100), seconds(spent).c_str(), seconds(left).c_str());
    const int shown = std::min({length, width_, static_cast<int>(sizeof line) - 1});
    if (shown <= 0) return;
    line[shown] = '\0';
    // A handler that runs while the line is redrawn erases the longer of the two.
    set_interrupt_erases_line(std::max(drawn_, shown));
    // A reader of stderr gone loses the line, not the image.
    const QuietBrokenPipe quiet;
    erase();  // or, the first time, go to the start of the line
    (void)std::fputs(line, stderr);
    (void)std::fflush(stderr);
    drawn_ = shown;
    set_interrupt_erases_line(drawn_);
}

// Goes to the start of the line, overwriting the line drawn, if any, with spaces: one
// write (stderr is unbuffered).
void ProgressSink::erase() const {
    const std::string blank =
        drawn_ == 0 ? "\r" : "\r" + std::string(static_cast<std::size_t>(drawn_), ' ') + "\r";
    (void)std::fputs(blank.c_str(), stderr);
}

void ProgressSink::clear_line() {
    if (drawn_ == 0) return;
    const QuietBrokenPipe quiet;
    erase();
    (void)std::fflush(stderr);
    set_interrupt_erases_line(0);
    drawn_ = 0;
}

}  // namespace rt
