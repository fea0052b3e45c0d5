#include "map/core/map_manifest.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <type_traits>

#include "map/core/map_codec.hpp"
#include "map/core/map_format.hpp"

namespace ltm::map {
namespace {

// A 64-bit hash, written as 16 lower-case hex digits.
template <class T>
struct Hex64 {
    T& v;
};
template <class T>
Hex64<T> hex(T& v) {
    return {v};
}

// A line pattern is "key <field> ...": the key is written, the whole pattern names the line in
// errors.
std::string key_of(const char* pattern) { return std::string(pattern, std::strcspn(pattern, " ")); }

class LineWriter {
  public:
    static constexpr bool kReading = false;

    LineWriter() { out_.precision(17); }
    template <class... T>
    void line(const char* pattern, T&&... fields) {
        out_ << key_of(pattern);
        ((out_ << ' ', put(fields)), ...);
        out_ << '\n';
    }
    template <class Problem>
    void check(bool /*ok*/, Problem&& /*problem*/) const {}
    void expect_end() const {}
    std::string text() const { return out_.str(); }

  private:
    template <class T>
    void put(const T& v) {
        out_ << v;
    }
    template <class T>
    void put(const Hex64<T>& h) {
        char buf[17];
        std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h.v));
        out_ << buf;
    }

    std::ostringstream out_;
};

class LineReader {
  public:
    static constexpr bool kReading = true;

    explicit LineReader(const std::string& text) : text_(text) { advance(); }

    // The key of the next line that has text; "" at the end.
    const std::string& peek() const { return tokens_.empty() ? kNone : tokens_[0]; }
    // How many fields the next line has after its key.
    std::size_t fields() const { return tokens_.empty() ? 0 : tokens_.size() - 1; }

    template <class... T>
    void line(const char* pattern, T&&... fields) {
        const std::string key = key_of(pattern);
        if (tokens_.empty()) {
            throw MapFormatError(kManifestFile,
                                 number_ == 0
                                     ? "empty: not an ltm map manifest"
                                     : "truncated: no '" + key + "' line (an interrupted write?)");
        }
        if (tokens_[0] != key) fail(unexpected(tokens_[0]) + " (expected '" + pattern + "')");
        constexpr std::size_t n = sizeof...(T);
        if (tokens_.size() > n + 1)
            fail("unexpected '" + tokens_[n + 1] + "' at the end of the line");
        std::size_t i = 1;
        const bool ok = tokens_.size() == n + 1 && (parse(tokens_[i++], fields) && ...);
        if (!ok) fail(std::string("expected '") + pattern + "'");
        last_number_ = number_;
        last_offset_ = offset_;
        advance();
    }

    // Fails for the line read last unless ok; the problem is a text or a function returning it.
    template <class Problem>
    void check(bool ok, Problem&& problem) const {
        if (ok) return;
        if constexpr (std::is_invocable<Problem>::value) {
            fail_at(last_number_, last_offset_, problem());
        } else {
            fail_at(last_number_, last_offset_, problem);
        }
    }
    // "'graph' out of place" for a key the manifest knows, else "unknown entry 'x'".
    static std::string unexpected(const std::string& key) {
        const bool known = key == "ltm_map" || key == "revision" || key == "descriptor" ||
                           key == "localisation_descriptor" || key == "session" || key == "graph" ||
                           key == "keyframes" || key == "local_map" || key == "end";
        return known ? "'" + key + "' out of place" : "unknown entry '" + key + "'";
    }
    // Fails for the next line.
    [[noreturn]] void fail(const std::string& problem) const { fail_at(number_, offset_, problem); }
    void expect_end() const {
        if (!tokens_.empty()) fail("text after 'end'");
    }

  private:
    [[noreturn]] static void fail_at(int number, std::uint64_t offset, const std::string& problem) {
        throw MapFormatError(kManifestFile, "line " + std::to_string(number), offset, problem);
    }

    // To the next line with text (tokens_ empty at the end).
    void advance() {
        tokens_.clear();
        while (tokens_.empty() && pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
            ++number_;
            offset_ = pos_;
            std::istringstream words(text_.substr(pos_, end - pos_));
            for (std::string w; words >> w;) tokens_.push_back(w);
            pos_ = end + 1;
        }
    }

    template <class T>
    static bool parse(const std::string& t, T& v) {
        if constexpr (std::is_same<T, std::string>::value) {
            v = t;
            return true;
        } else {
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
            return ec == std::errc() && end == t.data() + t.size();
        }
    }
    template <class T>
    static bool parse(const std::string& t, Hex64<T>& h) {
        if (t.size() != 16 || t.find_first_not_of("0123456789abcdef") != std::string::npos)
            return false;
        std::from_chars(t.data(), t.data() + t.size(), h.v, 16);
        return true;
    }

    static inline const std::string kNone;
    const std::string& text_;
    std::size_t pos_ = 0;
    std::vector<std::string> tokens_;
    int number_ = 0, last_number_ = 0;  // 1-based line numbers
    std::uint64_t offset_ = 0, last_offset_ = 0;
};

bool safe_relative(const std::string& f) {
    return !f.empty() && f[0] != '/' && f.find("..") == std::string::npos &&
           f.find_first_of(" \t\r\n") == std::string::npos;
}

// graphs: the graph entries so far.
template <class IO, class E>
void entry(IO& io, E& e, int& graphs) {
    if (e.kind == "graph") {
        io.line("graph <file> <size> <hash>", e.file, e.size, hex(e.hash));
        io.check(++graphs == 1, "a second graph entry");
    } else if (e.kind == "keyframes") {
        io.line("keyframes <file> <size> <hash> <first> <count>", e.file, e.size, hex(e.hash),
                e.first, e.count);
    } else if (e.kind == "local_map") {
        io.line("local_map <node> <file> <size> <hash>", e.node, e.file, e.size, hex(e.hash));
    } else if constexpr (IO::kReading) {
        io.fail(IO::unexpected(e.kind));
    }
    io.check(safe_relative(e.file),
             [&] { return "file name '" + e.file + "' is not a plain relative path"; });
}

// One "<key> <kind 0|1> <rings> <sectors> <max_range> <min_range> <sensor_height>" line.
template <class IO, class C>
void descriptor_line(IO& io, const char* pattern, const std::string& key, C& d) {
    int kind = static_cast<int>(d.kind);
    io.line(pattern, kind, d.rings, d.sectors, d.max_range, d.min_range, d.sensor_height);
    if constexpr (IO::kReading) {
        io.check(kind == 0 || kind == 1, key + " kind must be 0 or 1");
        d.kind = static_cast<places::ScanContextKind>(kind);
        if (const auto problem = validate(d)) {
            io.check(false, key + "." + problem->key + ": " + problem->problem);
        }
    }
}

// One "session <id> <first_stamp> <last_stamp> <added> <updated> [<robot>]" line (the robot of a
// map that several robots built; none when one robot built it); prev: the session before
// (reading: ids ascending).
template <class IO, class S>
void session_line(IO& io, S& s, const SessionRecord* prev) {
    bool named = !s.robot.empty();
    if constexpr (IO::kReading) named = io.fields() == 6;
    if (named) {
        io.line(
            "session <id> <first_stamp> <last_stamp> <local_maps_added> <local_maps_updated> "
            "<robot>",
            s.id, s.first_stamp, s.last_stamp, s.local_maps_added, s.local_maps_updated, s.robot);
    } else {
        io.line("session <id> <first_stamp> <last_stamp> <local_maps_added> <local_maps_updated>",
                s.id, s.first_stamp, s.last_stamp, s.local_maps_added, s.local_maps_updated);
    }
    if constexpr (IO::kReading) {
        io.check(std::isfinite(s.first_stamp) && std::isfinite(s.last_stamp) &&
                     s.first_stamp <= s.last_stamp,
                 "session stamps must be finite, the first not after the last");
        io.check(!prev || prev->id < s.id, [&] {
            return "session " + std::to_string(s.id) + " after session " +
                   std::to_string(prev->id) + " (ids ascending)";
        });
    }
}

template <class IO, class M>
void manifest(IO& io, M& m) {
    // Written: the format the localisation descriptors and the sessions call for (map_data.hpp).
    std::uint32_t version = map_format_for(m.localisation_descriptor, !m.sessions.empty());
    io.line("ltm_map <version>", version);
    io.check(readable_map_format(version), [&] { return unreadable_map_format(version); });
    io.line("revision <n>", m.revision);
    descriptor_line(
        io, "descriptor <kind 0|1> <rings> <sectors> <max_range> <min_range> <sensor_height>",
        "descriptor", m.descriptor);
    if (version >= 2) {
        descriptor_line(io,
                        "localisation_descriptor <kind 0|1> <rings> <sectors> <max_range> "
                        "<min_range> <sensor_height>",
                        "localisation_descriptor", m.localisation_descriptor);
    }
    if constexpr (IO::kReading) {
        m.version = version;
        if (version < 2) m.localisation_descriptor = no_localisation_descriptors();
        while (version >= 3 && io.peek() == "session") {
            SessionRecord s;
            session_line(io, s, m.sessions.empty() ? nullptr : &m.sessions.back());
            m.sessions.push_back(s);
        }
    } else if (version >= 3) {
        for (const SessionRecord& s : m.sessions) session_line(io, s, nullptr);
    }
    int graphs = 0;
    if constexpr (IO::kReading) {
        while (!io.peek().empty() && io.peek() != "end") {
            ManifestEntry e;
            e.kind = io.peek();
            entry(io, e, graphs);
            m.files.push_back(std::move(e));
        }
    } else {
        for (const ManifestEntry& e : m.files) entry(io, e, graphs);
    }
    std::size_t count = m.files.size();
    io.line("end <number of entries>", count);
    io.check(count == m.files.size(), [&] {
        return "'end' counts " + std::to_string(count) + " entries, the manifest has " +
               std::to_string(m.files.size());
    });
    io.expect_end();
    if constexpr (IO::kReading) {
        if (graphs == 0) throw MapFormatError(kManifestFile, "no 'graph' entry");
    }
}

}  // namespace

std::string write_manifest(const Manifest& m) {
    LineWriter w;
    manifest(w, m);
    return w.text();
}

Manifest parse_manifest(const std::string& text) {
    LineReader r(text);
    Manifest m;
    manifest(r, m);
    return m;
}

}  // namespace ltm::map
