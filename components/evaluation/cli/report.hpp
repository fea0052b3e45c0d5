#pragma once
// The numbers of one evaluation: printed as aligned text, written as metrics.txt and metrics.json.
#include <string>
#include <vector>

namespace ltm::eval::cli {

class Report {
  public:
    explicit Report(std::string title) : title_(std::move(title)) {}
    // Starts a group of values (a JSON object); keys are snake_case.
    void section(const std::string& name);
    void add(const std::string& key, double value, const std::string& unit = "");
    void add_count(const std::string& key, std::size_t value);
    void add_text(const std::string& key, const std::string& value);
    void note(const std::string& line);  // free text, in the text form only

    std::string text() const;
    std::string json() const;
    // Writes DIR/metrics.txt and DIR/metrics.json (creating DIR). Throws common::IoError.
    void write(const std::string& dir) const;

  private:
    struct Item {
        std::string section, key, value, unit;
        bool quoted = false, is_note = false;
    };
    std::string title_, current_ = "result";
    std::vector<Item> items_;
};

// Writes text to a file (creating the parent folder). Throws common::IoError.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace ltm::eval::cli
