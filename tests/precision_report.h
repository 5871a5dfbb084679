// The speed-vs-error report of tests/bench_precision.cpp: one row per scene and
// precision, written as a Markdown table, a CSV file and a hand-written SVG chart of
// render time against error.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "precision.h"

namespace report {

struct Row {
    std::string scene;
    std::string kind;       // "course" or "hard"
    std::string reference;  // what the error is measured against: "key" or "long double"
    precision::Real real;
    int width = 0, height = 0;
    double median_ms = 0;
    precision::Error error;
};

inline std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

inline std::string psnr_text(double psnr) { return std::isinf(psnr) ? "inf" : fixed(psnr, 1); }

// The 0.01% bar of issue 4: at most this share of pixels may differ.
inline bool within_bar(const precision::Error& e) { return precision::differing_percent(e) <= 0.01; }

// Time of each row relative to the double row of the same scene.
inline double ratio_to_double(const std::vector<Row>& rows, const Row& row) {
    for (const Row& r : rows)
        if (r.scene == row.scene && r.real == precision::Real::kDouble && r.median_ms > 0)
            return row.median_ms / r.median_ms;
    return 0;
}

inline std::string markdown(const std::vector<Row>& rows, const std::string& title,
                            const std::string& notes) {
    std::ostringstream out;
    out << "# " << title << "\n\n" << notes << "\n\n";

    // The summary: per precision, the total time and how many scenes miss the bar.
    out << "| precision | total time (ms) | time vs double | scenes within 0.01% | worst scene (% pixels "
           "differing) |\n|---|---:|---:|---:|---|\n";
    double double_total = 0;
    for (const Row& r : rows)
        if (r.real == precision::Real::kDouble) double_total += r.median_ms;
    for (precision::Real real :
         {precision::Real::kFloat, precision::Real::kDouble, precision::Real::kLongDouble}) {
        double total = 0;
        int scenes = 0, within = 0;
        const Row* worst = nullptr;
        for (const Row& r : rows) {
            if (r.real != real) continue;
            total += r.median_ms;
            ++scenes;
            if (within_bar(r.error)) ++within;
            if (r.error.differing_pixels > 0 &&
                (worst == nullptr ||
                 precision::differing_percent(r.error) > precision::differing_percent(worst->error)))
                worst = &r;
        }
        out << "| " << precision::name_of(real) << " | " << fixed(total, 1) << " | "
            << (double_total > 0 ? fixed(total / double_total, 2) : "-") << " | " << within << " of "
            << scenes << " | "
            << (worst ? worst->scene + " (" + fixed(precision::differing_percent(worst->error), 3) + "%)"
                      : "none")
            << " |\n";
    }

    out << "\n| scene | kind | size | precision | median ms | vs double | error against | pixels differing | "
           "% "
           "| largest | PSNR dB |\n|---|---|---|---|---:|---:|---|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
        out << "| " << r.scene << " | " << r.kind << " | " << r.width << "x" << r.height << " | "
            << precision::name_of(r.real) << " | " << fixed(r.median_ms, 2) << " | "
            << fixed(ratio_to_double(rows, r), 2) << " | " << r.reference << " | " << r.error.differing_pixels
            << " | " << fixed(precision::differing_percent(r.error), 4)
            << (within_bar(r.error) ? "" : " **!**") << " | " << r.error.largest_difference << " | "
            << psnr_text(r.error.psnr) << " |\n";
    }
    return out.str();
}

inline std::string csv(const std::vector<Row>& rows) {
    std::ostringstream out;
    out << "scene,kind,width,height,precision,median_ms,time_vs_double,reference,differing_pixels,pixels,"
           "differing_percent,largest_difference,psnr_db\n";
    for (const Row& r : rows) {
        out << r.scene << "," << r.kind << "," << r.width << "," << r.height << ","
            << precision::name_of(r.real) << "," << fixed(r.median_ms, 3) << ","
            << fixed(ratio_to_double(rows, r), 3) << "," << r.reference << "," << r.error.differing_pixels
            << "," << r.error.pixels << "," << fixed(precision::differing_percent(r.error), 5) << ","
            << r.error.largest_difference << "," << psnr_text(r.error.psnr) << "\n";
    }
    return out.str();
}

// A log-log scatter plot: x the median render time, y the share of pixels differing
// from the reference. Exact images (0%) sit on their own row at the bottom. Each point
// has a tooltip (<title>) naming its scene.
inline std::string svg(const std::vector<Row>& rows, const std::string& title) {
    const double width = 760, height = 490, left = 70, right = 170, top = 40, bottom = 80;
    const double plot_w = width - left - right, plot_h = height - top - bottom;
    double min_ms = 1e300, max_ms = 0;
    for (const Row& r : rows) {
        min_ms = std::min(min_ms, std::max(r.median_ms, 1e-3));
        max_ms = std::max(max_ms, std::max(r.median_ms, 1e-3));
    }
    const double x_lo = std::floor(std::log10(min_ms)),
                 x_hi = std::max(x_lo + 1, std::ceil(std::log10(max_ms)));
    const double y_lo = -4, y_hi = 2;  // 1e-4 % .. 100 %; exact images below y_lo
    const double exact_row = top + plot_h + 22;
    auto x_of = [&](double ms) {
        return left + plot_w * (std::log10(std::max(ms, 1e-3)) - x_lo) / (x_hi - x_lo);
    };
    auto y_of = [&](double percent) {
        if (percent <= 0) return exact_row;
        const double v = std::min(std::max(std::log10(percent), y_lo), y_hi);
        return top + plot_h * (y_hi - v) / (y_hi - y_lo);
    };
    const std::map<precision::Real, const char*> colour = {{precision::Real::kFloat, "#d62728"},
                                                           {precision::Real::kDouble, "#1f77b4"},
                                                           {precision::Real::kLongDouble, "#2ca02c"}};
    std::ostringstream out;
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" viewBox=\"0 0 " << width << " " << height
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    out << "<text x=\"" << left << "\" y=\"22\" font-size=\"15\">" << title << "</text>\n";
    for (int decade = static_cast<int>(x_lo); decade <= static_cast<int>(x_hi); ++decade) {
        const double e = decade;
        const double x = x_of(std::pow(10.0, e));
        out << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + plot_h
            << "\" stroke=\"#ddd\"/><text x=\"" << x << "\" y=\"" << top + plot_h + 44
            << "\" text-anchor=\"middle\">" << fixed(std::pow(10.0, e), e < 0 ? int(-e) : 0) << "</text>\n";
    }
    for (int decade = static_cast<int>(y_lo); decade <= static_cast<int>(y_hi); ++decade) {
        const double e = decade;
        const double y = top + plot_h * (y_hi - e) / (y_hi - y_lo);
        out << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plot_w << "\" y2=\"" << y
            << "\" stroke=\"#ddd\"/><text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
            << (e < 0 ? fixed(std::pow(10.0, e), int(-e)) : fixed(std::pow(10.0, e), 0)) << "%</text>\n";
    }
    const double bar = top + plot_h * (y_hi - std::log10(0.01)) / (y_hi - y_lo);
    out << "<line x1=\"" << left << "\" y1=\"" << bar << "\" x2=\"" << left + plot_w << "\" y2=\"" << bar
        << "\" stroke=\"#888\" stroke-dasharray=\"6 4\"/><text x=\"" << left + plot_w - 4 << "\" y=\""
        << bar - 5 << "\" text-anchor=\"end\" fill=\"#555\">0.01% bar</text>\n";
    out << "<text x=\"" << left - 6 << "\" y=\"" << exact_row + 4 << "\" text-anchor=\"end\">exact</text>\n";
    out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plot_w << "\" height=\"" << plot_h
        << "\" fill=\"none\" stroke=\"#333\"/>\n";
    out << "<text x=\"" << left + plot_w / 2 << "\" y=\"" << height - 8
        << "\" text-anchor=\"middle\">median render time (ms, log scale)</text>\n";
    out << "<text transform=\"translate(16 " << top + plot_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\">pixels differing from reference (log scale)</text>\n";
    for (const Row& r : rows) {
        const double x = x_of(r.median_ms), y = y_of(precision::differing_percent(r.error));
        out << "<circle cx=\"" << fixed(x, 1) << "\" cy=\"" << fixed(y, 1) << "\" r=\"5\" fill=\""
            << colour.at(r.real) << "\" fill-opacity=\"0.7\" stroke=\""
            << (r.kind == "hard" ? "#000" : "none") << "\"><title>" << r.scene << " (" << r.kind << "), "
            << precision::name_of(r.real) << ": " << fixed(r.median_ms, 2) << " ms, "
            << fixed(precision::differing_percent(r.error), 4) << "% pixels differ, largest "
            << r.error.largest_difference << "</title></circle>\n";
    }
    double legend_y = top + 10;
    for (const auto& [real, fill] : colour) {
        out << "<circle cx=\"" << width - right + 20 << "\" cy=\"" << legend_y << "\" r=\"5\" fill=\"" << fill
            << "\"/><text x=\"" << width - right + 32 << "\" y=\"" << legend_y + 4 << "\">"
            << precision::name_of(real) << "</text>\n";
        legend_y += 20;
    }
    out << "<circle cx=\"" << width - right + 20 << "\" cy=\"" << legend_y
        << "\" r=\"5\" fill=\"#fff\" stroke=\"#000\"/><text x=\"" << width - right + 32 << "\" y=\""
        << legend_y + 4 << "\">hard case (outlined)</text>\n";
    out << "<circle cx=\"" << width - right + 20 << "\" cy=\"" << legend_y + 20
        << "\" r=\"5\" fill=\"#bbb\"/><text x=\"" << width - right + 32 << "\" y=\"" << legend_y + 24
        << "\">course scene</text>\n";
    out << "</svg>\n";
    return out.str();
}

inline bool write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    return static_cast<bool>(out);
}

}  // namespace report
