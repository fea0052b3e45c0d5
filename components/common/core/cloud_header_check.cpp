#include "common/core/cloud_header_check.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "common/core/io_error.hpp"

namespace ltm::common {

// PCL 1.13's PCDReader crashes on some malformed headers (seen: a text file without FIELDS), so
// the header is checked here first: every key PCL needs, sane counts, and enough bytes of data.
void check_pcd_header(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path, "cannot open");
    std::map<std::string, std::vector<std::string>> keys;
    std::string line;
    std::size_t header_bytes = 0;
    for (int lineno = 1; lineno <= 64 && std::getline(in, line); ++lineno) {
        header_bytes += line.size() + 1;
        if (line.empty() || line[0] == '#') continue;
        // PCL splits header lines at spaces, tabs and carriage returns only.
        for (const char c : line)
            if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
                throw IoError(
                    path, "PCD header line " + std::to_string(lineno) + ": a control character");
        std::istringstream ss(line);
        std::string key, v;
        ss >> key;
        if (key != "VERSION" && key != "FIELDS" && key != "SIZE" && key != "TYPE" &&
            key != "COUNT" && key != "WIDTH" && key != "HEIGHT" && key != "VIEWPOINT" &&
            key != "POINTS" && key != "DATA")
            throw IoError(path, "not a PCD file: unexpected '" + key.substr(0, 32) +
                                    "' on header line " + std::to_string(lineno));
        while (ss >> v) keys[key].push_back(v);
        if (key == "DATA") break;
    }
    // PCL reads on after DATA while lines are empty, comments or start like a header key, and
    // parses those again as header lines; such a line is refused here.
    static const char* const kPclKeys[] = {"VERSION",   "FIELDS", "COLUMNS", "SIZE",
                                           "TYPE",      "COUNT",  "WIDTH",   "HEIGHT",
                                           "VIEWPOINT", "POINTS", "DATA"};
    for (int more = 0; more < 64 && std::getline(in, line); ++more) {
        if (line.empty()) continue;
        std::istringstream ss(line);  // PCL's first word: leading whitespace skipped
        std::string first;
        ss >> first;
        if (first.empty()) break;
        if (first[0] == '#') continue;
        for (const char* k : kPclKeys)
            if (first.rfind(k, 0) == 0)
                throw IoError(path, std::string("PCD header: a ") + k + " line after DATA");
        break;
    }
    for (const char* k : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS", "DATA"})
        if (keys[k].empty()) throw IoError(path, std::string("PCD header has no ") + k + " line");
    const std::size_t nf = keys["FIELDS"].size();
    if (keys["SIZE"].size() != nf || keys["TYPE"].size() != nf ||
        (!keys["COUNT"].empty() && keys["COUNT"].size() != nf))
        throw IoError(path, "PCD header: FIELDS, SIZE, TYPE and COUNT differ in length");
    // Counts as digits only (atol would wrap a huge POINTS into a small or negative one).
    auto count = [&](const std::string& text, std::uint64_t max, const char* what) {
        if (text.empty() || text.size() > 10 ||
            text.find_first_not_of("0123456789") != std::string::npos || std::stoull(text) > max)
            throw IoError(path,
                          std::string("PCD header: bad ") + what + " '" + text.substr(0, 32) + "'");
        return std::stoull(text);
    };
    constexpr std::uint64_t kMaxU32 = 0xffffffffu;
    std::uint64_t step = 0;
    for (std::size_t i = 0; i < nf; ++i) {
        const std::uint64_t size = count(keys["SIZE"][i], 8, "SIZE");
        const std::string& type = keys["TYPE"][i];
        if (!(type == "F" && (size == 4 || size == 8)) && type != "I" && type != "U")
            throw IoError(path, "PCD header: bad TYPE '" + type.substr(0, 32) + "' of size " +
                                    std::to_string(size));
        const std::uint64_t n = keys["COUNT"].empty() ? 1 : count(keys["COUNT"][i], 65535, "COUNT");
        if (size != 1 && size != 2 && size != 4 && size != 8)
            throw IoError(path, "PCD header: bad SIZE");
        if (n < 1) throw IoError(path, "PCD header: bad COUNT");
        step += size * n;
    }
    const std::uint64_t points = count(keys["POINTS"][0], kMaxU32, "POINTS");
    const std::uint64_t width = count(keys["WIDTH"][0], kMaxU32, "WIDTH");
    const std::uint64_t height =
        keys["HEIGHT"].empty() ? 1 : count(keys["HEIGHT"][0], kMaxU32, "HEIGHT");
    if (width * height != points) throw IoError(path, "PCD header: WIDTH x HEIGHT is not POINTS");
    const std::uint64_t file_size = std::filesystem::file_size(path);
    const std::uint64_t data_bytes = file_size > header_bytes ? file_size - header_bytes : 0;
    const std::string& data = keys["DATA"][0];
    // What PCL allocates (points x step) must be backed by the file: every byte when binary, a
    // character a point when ascii, a generous compression ratio when binary_compressed.
    if (data == "binary") {
        if (data_bytes < points * step)
            throw IoError(path, "truncated: " + std::to_string(file_size) + " bytes, header says " +
                                    std::to_string(header_bytes + points * step));
    } else if (data == "ascii") {
        if (points > data_bytes)
            throw IoError(path, "truncated: " + std::to_string(points) + " points in " +
                                    std::to_string(data_bytes) + " bytes of text");
    } else if (data == "binary_compressed") {
        // Two sizes lead the data; PCL trusts them (an uncompressed size of 0 made it copy from a
        // null buffer).
        std::uint32_t sizes[2] = {0, 0};  // compressed, uncompressed
        in.clear();
        in.seekg(static_cast<std::streamoff>(header_bytes));
        if (!in.read(reinterpret_cast<char*>(sizes), sizeof sizes))
            throw IoError(path, "truncated: no compressed sizes after the header");
        if (sizes[1] != points * step)
            throw IoError(path, "PCD binary_compressed: uncompressed size " +
                                    std::to_string(sizes[1]) + ", the header says " +
                                    std::to_string(points * step));
        if (sizes[0] > data_bytes - sizeof sizes || (sizes[1] > 0 && sizes[0] == 0))
            throw IoError(path, "PCD binary_compressed: compressed size " +
                                    std::to_string(sizes[0]) + " does not fit the " +
                                    std::to_string(data_bytes - sizeof sizes) + " bytes after it");
        if (points * step > 1024 * data_bytes)
            throw IoError(path, "truncated: " + std::to_string(points * step) +
                                    " bytes of points in " + std::to_string(data_bytes) +
                                    " compressed bytes");
    } else {
        throw IoError(path, "PCD header: unknown DATA '" + data.substr(0, 32) + "'");
    }
}

// PCL 1.13's PLYReader asserts on a list property in the vertex element, ignores lines it does
// not know, and allocates what a header claims before reading: the header is checked here first
// (the keywords PCL understands, known types, and, for binary files, enough bytes for every
// element's fixed-size part).
void check_ply_header(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path, "cannot open");
    auto fail = [&](int lineno, const std::string& problem) {
        throw IoError(path, "PLY header line " + std::to_string(lineno) + ": " + problem);
    };
    auto type_size = [](const std::string& t) -> std::size_t {
        if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
        if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
        if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" ||
            t == "float32")
            return 4;
        if (t == "double" || t == "float64") return 8;
        return 0;
    };
    struct Element {
        std::string name;
        std::uint64_t count = 0;
        std::uint64_t min_row = 0;  // bytes of a row in a binary file (lists: their count only)
        std::size_t properties = 0;
    };
    std::vector<Element> elements;
    std::string line, format;
    std::uint64_t header_bytes = 0;
    int lineno = 0;
    bool end = false;
    while (!end && lineno < 1000 && std::getline(in, line)) {
        ++lineno;
        header_bytes += line.size() + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (lineno == 1) {
            if (line != "ply") throw IoError(path, "not a PLY file: no 'ply' on the first line");
            continue;
        }
        // PCL splits its header lines at spaces and tabs only (and asserted on an obj_info line
        // it had found by another split): a line must start with its keyword.
        if (line.empty() || line[0] == ' ' || line[0] == '\t')
            fail(lineno, "empty or indented header line");
        for (const char c : line)
            if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
                fail(lineno, "a control character");
        std::istringstream ss(line);
        std::string key;
        ss >> key;
        if (key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            std::string version;
            ss >> format >> version;
            if (format != "ascii" && format != "binary_little_endian" &&
                format != "binary_big_endian")
                fail(lineno, "unknown format");
        } else if (key == "element") {
            Element e;
            std::string count;
            if (!(ss >> e.name >> count) ||
                count.find_first_not_of("0123456789") != std::string::npos || count.size() > 12)
                fail(lineno, "expected 'element NAME COUNT'");
            e.count = std::stoull(count);
            elements.push_back(e);
        } else if (key == "property") {
            if (elements.empty()) fail(lineno, "a property before any element");
            Element& e = elements.back();
            std::string type, name;
            ss >> type;
            if (type == "list") {
                std::string count_type, item_type;
                ss >> count_type >> item_type >> name;
                if (type_size(count_type) == 0 || type_size(item_type) == 0 || name.empty())
                    fail(lineno, "expected 'property list COUNT_TYPE TYPE NAME' with known types");
                if (e.name == "vertex")
                    fail(lineno, "a list property in the vertex element is not supported");
                e.min_row += type_size(count_type);
            } else {
                ss >> name;
                if (type_size(type) == 0 || name.empty())
                    fail(lineno, "expected 'property TYPE NAME' with a known type");
                e.min_row += type_size(type);
            }
            ++e.properties;
        } else if (key == "end_header") {
            end = true;
        } else {
            fail(lineno, "unknown keyword '" + key.substr(0, 32) + "'");
        }
        std::string extra;
        if (ss >> extra) fail(lineno, "unexpected '" + extra.substr(0, 32) + "' at the end");
    }
    if (!end) throw IoError(path, "PLY header has no end_header line");
    if (format.empty()) throw IoError(path, "PLY header has no format line");
    const std::uint64_t file_bytes = std::filesystem::file_size(path);
    const std::uint64_t data_bytes = file_bytes > header_bytes ? file_bytes - header_bytes : 0;
    std::uint64_t need = 0;  // binary: bytes; ascii: values (each at least one character)
    for (const Element& e : elements) {
        const std::uint64_t per_row = format == "ascii" ? e.properties : e.min_row;
        if (per_row > 0 && e.count > data_bytes / per_row)
            throw IoError(path, "truncated: element " + e.name + " of " + std::to_string(e.count) +
                                    " rows does not fit in the " + std::to_string(data_bytes) +
                                    " bytes after the header");
        need += e.count * per_row;
    }
    if (need > data_bytes)
        throw IoError(path, "truncated: the elements need " + std::to_string(need) + " bytes, " +
                                std::to_string(data_bytes) + " follow the header");
}

}  // namespace ltm::common
