#pragma once
// A self-contained HTML page (no external file, script or font): sections of text, tables,
// pictures embedded as data URIs (SVG, PNG) and collapsed text. ltm_eval report builds the run
// report with it.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace ltm::eval {

std::string html_escape(const std::string& text);
std::string base64(const std::string& bytes);

class HtmlReport {
  public:
    explicit HtmlReport(std::string title) : title_(std::move(title)) {}

    void section(const std::string& heading);  // a new section, listed in the contents
    void paragraph(const std::string& text);   // escaped
    void table(const std::vector<std::string>& header,
               const std::vector<std::vector<std::string>>& rows);  // cells escaped
    void svg(const std::string& svg_text, const std::string& caption);
    void png(const std::string& png_bytes, const std::string& caption);
    void collapsed(const std::string& summary, const std::string& text);  // <details><pre>
    // A table of files: relative link, size.
    void files(const std::vector<std::pair<std::string, std::uintmax_t>>& entries);

    std::string html() const;
    std::size_t sections() const { return headings_.size(); }

  private:
    void figure(const std::string& mime, const std::string& bytes, const std::string& caption);
    std::string title_;
    std::vector<std::string> headings_;
    std::string body_;
};

}  // namespace ltm::eval
