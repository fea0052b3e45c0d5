#include "evaluation/core/eval_io.hpp"

#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace ltm::eval {
namespace {

bool blank(const std::string& line) {
    const auto first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

std::string at_line(int lineno, const std::string& what) {
    return "line " + std::to_string(lineno) + ": " + what;
}

}  // namespace

std::vector<std::uint32_t> read_labels(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw common::IoError(path, "cannot open");
    const std::streamsize bytes = in.tellg();
    if (bytes % 4 != 0)
        throw common::IoError(path, "size is not a multiple of 4 bytes (uint32 labels)");
    std::vector<std::uint32_t> labels(static_cast<std::size_t>(bytes / 4));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(labels.data()), bytes))
        throw common::IoError(path, "read failed");
    return labels;
}

void write_labels(const std::string& path, const std::vector<std::uint32_t>& labels) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw common::IoError(path, "cannot open for writing");
    out.write(reinterpret_cast<const char*>(labels.data()),
              static_cast<std::streamsize>(labels.size() * 4));
    if (!out.flush()) throw common::IoError(path, "write failed");
}

std::vector<LoopPair> read_loop_pairs(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw common::IoError(path, "cannot open");
    std::vector<LoopPair> out;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (blank(line)) continue;
        std::istringstream ss(line);
        long long q = -1, m = -1;
        if (!(ss >> q >> m) || q < 0 || m < 0)
            throw common::IoError(path,
                                  at_line(lineno, "expected `query match [score]` frame indices"));
        LoopPair p;
        p.query = static_cast<std::size_t>(q);
        p.match = static_cast<std::size_t>(m);
        if (!(ss >> p.score)) p.score = 0.0;
        out.push_back(p);
    }
    return out;
}

void write_loop_pairs(const std::string& path, const std::vector<LoopPair>& loops) {
    std::ofstream out(path);
    if (!out) throw common::IoError(path, "cannot open for writing");
    for (const auto& l : loops) out << l.query << ' ' << l.match << ' ' << l.score << '\n';
    if (!out.flush()) throw common::IoError(path, "write failed");
}

RelocAttempts read_reloc_attempts(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw common::IoError(path, "cannot open");
    RelocAttempts out;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (blank(line)) continue;
        std::istringstream ss(line);
        long long frame = -1;
        int ok = -1;
        RelocAttempt a;
        if (!(ss >> frame >> a.time_s >> ok) || frame < 0 || (ok != 0 && ok != 1))
            throw common::IoError(
                path, at_line(lineno, "expected `frame time_s ok(0|1) [12 pose numbers]`"));
        a.frame = static_cast<std::size_t>(frame);
        a.has_pose = ok == 1;
        if (a.has_pose) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c)
                    if (!(ss >> a.pose.matrix()(r, c)))
                        throw common::IoError(
                            path, at_line(lineno, "ok = 1 needs a 3x4 pose (12 numbers)"));
        }
        out.push_back(a);
    }
    return out;
}

}  // namespace ltm::eval
