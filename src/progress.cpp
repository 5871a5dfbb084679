#include "raytracer/progress.h"

#include <cstdio>
#include <string>

#include "raytracer/interrupts.h"

#ifdef _WIN32
#include <io.h>
#else
#include <unistd.h>
#endif

namespace rt {

namespace {

std::string seconds(double s) {
    char text[32];
    if (s < 60) {
        (void)std::snprintf(text, sizeof text, "%.0f s", s);
    } else {
        const long whole = static_cast<long>(s);
        (void)std::snprintf(text, sizeof text, "%ld:%02ld min", whole / 60, whole % 60);
    }
    return text;
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
      next_draw_(start_ + kFirstAfter) {}

void ProgressSink::rows_finished(int count) {
    if (!enabled_) return;
    done_ = count;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_draw_ || done_ >= total_) return;
    next_draw_ = now + kRedrawEvery;
    draw(now - start_);
}

void ProgressSink::draw(std::chrono::steady_clock::duration elapsed) {
    const double spent = std::chrono::duration<double>(elapsed).count();
    const double fraction = total_ <= 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_);
    const double left = fraction > 0 ? spent * (1 - fraction) / fraction : 0;
    char line[96];
    (void)std::snprintf(line, sizeof line, "\rraytracer.exe: %3d%% of rows, %s elapsed, about %s left ",
                        static_cast<int>(fraction * 100), seconds(spent).c_str(), seconds(left).c_str());
    (void)std::fputs(drawn_ ? kEraseLine : "\r", stderr);
    (void)std::fputs(line, stderr);
    (void)std::fflush(stderr);
    if (!drawn_) set_interrupt_erases_line(true);
    drawn_ = true;
}

void ProgressSink::finish() {
    if (!drawn_) return;
    (void)std::fputs(kEraseLine, stderr);
    (void)std::fflush(stderr);
    set_interrupt_erases_line(false);
    drawn_ = false;
}

}  // namespace rt
