#include "evaluation/core/html_report.hpp"

#include <cstdint>
#include <cstdio>

namespace ltm::eval {

std::string html_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string base64(const std::string& bytes) {
    static const char* const kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = (static_cast<std::uint8_t>(bytes[i]) << 16) |
                                (static_cast<std::uint8_t>(bytes[i + 1]) << 8) |
                                static_cast<std::uint8_t>(bytes[i + 2]);
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (i < bytes.size()) {
        std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

namespace {

std::string anchor(std::size_t index) { return "s" + std::to_string(index); }

std::string size_text(std::uintmax_t bytes) {
    char buffer[32];
    if (bytes >= (1u << 20)) {
        std::snprintf(buffer, sizeof buffer, "%.1f MB", bytes / 1048576.0);
    } else if (bytes >= 1024) {
        std::snprintf(buffer, sizeof buffer, "%.1f kB", bytes / 1024.0);
    } else {
        std::snprintf(buffer, sizeof buffer, "%ju B", bytes);
    }
    return buffer;
}

}  // namespace

void HtmlReport::section(const std::string& heading) {
    if (!headings_.empty()) body_ += "</section>\n";
    body_ +=
        "<section id=\"" + anchor(headings_.size()) + "\"><h2>" + html_escape(heading) + "</h2>\n";
    headings_.push_back(heading);
}

void HtmlReport::paragraph(const std::string& text) {
    body_ += "<p>" + html_escape(text) + "</p>\n";
}

void HtmlReport::table(const std::vector<std::string>& header,
                       const std::vector<std::vector<std::string>>& rows) {
    body_ += "<table><thead><tr>";
    for (const std::string& h : header) body_ += "<th>" + html_escape(h) + "</th>";
    body_ += "</tr></thead><tbody>\n";
    for (const auto& row : rows) {
        body_ += "<tr>";
        for (const std::string& cell : row) body_ += "<td>" + html_escape(cell) + "</td>";
        body_ += "</tr>\n";
    }
    body_ += "</tbody></table>\n";
}

void HtmlReport::figure(const std::string& mime, const std::string& bytes,
                        const std::string& caption) {
    body_ += "<figure><img alt=\"" + html_escape(caption) + "\" src=\"data:" + mime + ";base64," +
             base64(bytes) + "\"><figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
}

void HtmlReport::svg(const std::string& svg_text, const std::string& caption) {
    figure("image/svg+xml", svg_text, caption);
}

void HtmlReport::png(const std::string& png_bytes, const std::string& caption) {
    figure("image/png", png_bytes, caption);
}

void HtmlReport::collapsed(const std::string& summary, const std::string& text) {
    body_ += "<details><summary>" + html_escape(summary) + "</summary><pre>" + html_escape(text) +
             "</pre></details>\n";
}

void HtmlReport::files(const std::vector<std::pair<std::string, std::uintmax_t>>& entries) {
    body_ += "<table><thead><tr><th>file</th><th>size</th></tr></thead><tbody>\n";
    for (const auto& [path, bytes] : entries) {
        body_ += "<tr><td><a href=\"" + html_escape(path) + "\">" + html_escape(path) +
                 "</a></td><td>" + size_text(bytes) + "</td></tr>\n";
    }
    body_ += "</tbody></table>\n";
}

std::string HtmlReport::html() const {
    std::string out =
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
        html_escape(title_) +
        "</title>\n<style>\n"
        "body{font-family:sans-serif;margin:0 auto;max-width:960px;padding:1em;color:#222}\n"
        "h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}\n"
        "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ddd;"
        "padding:2px 8px;text-align:left;font-size:.9em}th{background:#f3f3f3}\n"
        "figure{margin:.5em 0}img{max-width:100%;border:1px solid #eee}"
        "figcaption{font-size:.85em;color:#555}\n"
        "pre{background:#f7f7f7;padding:.5em;overflow-x:auto;font-size:.8em}\n"
        "nav a{margin-right:1em}\n</style></head>\n<body>\n<h1>" +
        html_escape(title_) + "</h1>\n<nav>";
    for (std::size_t i = 0; i < headings_.size(); ++i) {
        out += "<a href=\"#" + anchor(i) + "\">" + html_escape(headings_[i]) + "</a>";
    }
    out += "</nav>\n" + body_;
    if (!headings_.empty()) out += "</section>\n";
    // Once loaded: a picture the browser could not show is said on the page and in the console
    // (the render test reads both), and counted on <body>.
    out +=
        "<script>window.addEventListener('load',function(){var n=0;"
        "Array.prototype.forEach.call(document.images,function(i){if(!i.complete||"
        "i.naturalWidth===0){n++;console.error('report: picture not shown: '+i.alt);"
        "var p=document.createElement('p');p.textContent='(picture not shown: '+i.alt+')';"
        "i.parentNode.insertBefore(p,i);}});"
        "document.body.setAttribute('data-pictures',document.images.length);"
        "document.body.setAttribute('data-pictures-broken',n);});</script>\n";
    out += "</body></html>\n";
    return out;
}

}  // namespace ltm::eval
