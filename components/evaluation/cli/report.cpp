#include "evaluation/cli/report.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"

namespace ltm::eval::cli {
namespace {

std::string format_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out;
}

}  // namespace

void Report::section(const std::string& name) { current_ = name; }

void Report::add(const std::string& key, double value, const std::string& unit) {
    items_.push_back({current_, key, format_number(value), unit, false, false});
}

void Report::add_count(const std::string& key, std::size_t value) {
    items_.push_back({current_, key, std::to_string(value), "", false, false});
}

void Report::add_text(const std::string& key, const std::string& value) {
    items_.push_back({current_, key, value, "", true, false});
}

void Report::note(const std::string& line) {
    items_.push_back({current_, "", line, "", false, true});
}

std::string Report::text() const {
    std::string out = title_ + "\n";
    std::string section;
    for (const auto& it : items_) {
        if (it.section != section) {
            section = it.section;
            out += "[" + section + "]\n";
        }
        if (it.is_note) {
            out += "  " + it.value + "\n";
            continue;
        }
        std::string key = it.key + (it.unit.empty() ? "" : " [" + it.unit + "]");
        if (key.size() < 34) key.resize(34, ' ');
        out += "  " + key + " " + it.value + "\n";
    }
    return out;
}

std::string Report::json() const {
    std::string out = "{\n  \"title\": \"" + json_escape(title_) + "\"";
    std::string section;
    bool open = false;
    for (const auto& it : items_) {
        if (it.is_note) continue;
        if (it.section != section || !open) {
            out += open ? "\n  }" : "";
            out += ",\n  \"" + json_escape(it.section) + "\": {";
            section = it.section;
            open = true;
        } else {
            out += ",";
        }
        std::string key = it.key;
        if (!it.unit.empty()) {
            std::string unit;
            for (char c : it.unit) {
                if (c == '%')
                    unit += "pct";
                else if (c == '/')
                    unit += "_per_";
                else if (c == ' ')
                    unit += '_';
                else
                    unit += c;
            }
            key += "_" + unit;
        }
        out += "\n    \"" + json_escape(key) + "\": ";
        out += it.quoted ? "\"" + json_escape(it.value) + "\"" : it.value;
    }
    out += open ? "\n  }\n}\n" : "\n}\n";
    return out;
}

void Report::write(const std::string& dir) const {
    write_text_file((std::filesystem::path(dir) / "metrics.txt").string(), text());
    write_text_file((std::filesystem::path(dir) / "metrics.json").string(), json());
}

void write_text_file(const std::string& path, const std::string& text) {
    const std::filesystem::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
    std::ofstream out(path);
    if (!out) throw common::IoError(path, "cannot open for writing");
    out << text;
    if (!out.flush()) throw common::IoError(path, "write failed");
}

}  // namespace ltm::eval::cli
