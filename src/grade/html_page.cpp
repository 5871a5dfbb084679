#include "html_page.h"

#include <cctype>
#include <cstdio>
#include <sstream>

#include "raytracer/output_file.h"
#include "report.h"

namespace fs = std::filesystem;

namespace grade {
namespace {

std::string escaped(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '&':
                out += "&amp;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// A relative URL: the path's bytes, with everything but unreserved characters and '/' escaped.
std::string url_of(const fs::path& relative) {
    std::string url;
    for (const char c : relative.generic_u8string()) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') {
            url += c;
        } else {
            char hex[4];
            std::snprintf(hex, sizeof hex, "%%%02X", byte);
            url += hex;
        }
    }
    return url;
}

void write_row(std::ostream& out, const SceneResult& r) {
    const std::string verdict = r.passed() ? "pass" : "FAIL";
    std::string detail = r.problem.empty() ? describe_differences(r.judgement) : r.problem;
    for (const std::string& note : r.notes) detail += "; note: " + note;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3f", r.seconds);
    out << "<tr class=\"" << (r.passed() ? "pass" : "fail") << "\"><td>" << escaped(r.name) << "</td><td>"
        << verdict << "</td><td>" << (r.passed() ? kMarksPerScene : 0) << "/" << kMarksPerScene << "</td><td>"
        << seconds << "</td><td>" << escaped(detail) << "</td></tr>\n";
}

void write_picture(std::ostream& out, const SceneResult& r, const std::string& url) {
    const Judgement& j = r.judgement;
    out << "<h2>" << escaped(r.name) << "</h2>\n<p>" << escaped(describe_differences(j)) << ".";
    if (!j.unexplained_box.empty())
        out << " The unexplained pixels lie in x " << j.unexplained_box.left << ".."
            << j.unexplained_box.right << ", y " << j.unexplained_box.top << ".." << j.unexplained_box.bottom
            << ".";
    out << "</p>\n<ul>\n";
    for (const PixelDifference& d : j.first_unexplained)
        out << "<li>" << escaped(describe_pixel(d)) << "</li>\n";
    out << "</ul>\n<p class=\"panels\"><span>key</span><span>yours</span><span>difference</span></p>\n"
        << "<img src=\"" << url << "\" alt=\"" << escaped(r.name) << ": key, yours, difference\">\n";
}

}  // namespace

std::string write_html_page(const fs::path& page, const std::vector<SceneResult>& results,
                            const std::vector<fs::path>& pictures, const std::string& summary) {
    std::ostringstream out;
    out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        << "<title>raytracer-grade: " << escaped(summary) << "</title>\n<style>\n"
        << "body { font-family: sans-serif; margin: 1.5em; }\n"
        << "table { border-collapse: collapse; } td, th { border: 1px solid #999; padding: 0.2em 0.6em; }\n"
        << "tr.pass td:nth-child(2) { color: #060; } tr.fail td:nth-child(2) { color: #b00; font-weight: "
           "bold; }\n"
        << "img { max-width: 100%; image-rendering: pixelated; border: 1px solid #999; }\n"
        << ".panels span { display: inline-block; width: 33%; text-align: center; }\n"
        << "</style>\n</head>\n<body>\n<h1>" << escaped(summary) << "</h1>\n"
        << "<p>Difference panel: dimmed key where equal; dark blue: off by one level; yellow: a "
           "known ambiguous pixel showing the other outcome (allowed); red: unexplained, ringed in "
           "magenta when few.</p>\n"
        << "<table>\n<tr><th>scene</th><th>result</th><th>marks</th><th>time s</th><th>details</th></tr>\n";
    for (const SceneResult& r : results) write_row(out, r);
    out << "</table>\n";
    std::error_code ec;
    // Lexical, on normal paths: fs::relative() follows links (a page's folder reached
    // through one got links the browser resolves elsewhere); a ".." left in would
    // mislead lexically_relative().
    const fs::path folder = fs::absolute(page, ec).lexically_normal().parent_path();
    for (std::size_t i = 0; i < results.size(); ++i)
        if (!pictures[i].empty())
            write_picture(
                out, results[i],
                url_of(fs::absolute(pictures[i], ec).lexically_normal().lexically_relative(folder)));
    out << "</body>\n</html>\n";

    const std::string text = out.str();
    if (page.has_parent_path()) fs::create_directories(page.parent_path(), ec);  // as --diff-dir's folder
    return rt::write_whole_file(page.u8string().c_str(), text.data(), text.size());
}

}  // namespace grade
