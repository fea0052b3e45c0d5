#pragma once
// Error messages quote outside input (a YAML key, a parser's complaint about a character, a word
// of a file header). one_line() keeps such a message one line: line breaks and other control
// characters are shown escaped ("\n", "\x01").
#include <cstdio>
#include <string>

namespace ltm::common {

inline std::string one_line(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if ((u < 0x20 && c != '\t') || u == 0x7f) {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", u);
            out += hex;
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace ltm::common
