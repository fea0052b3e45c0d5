#include "recorder/core/mcap_info.hpp"

#include <algorithm>
#include <cstdio>

#include "recorder/core/mcap_reader.hpp"

namespace ltm::recorder {
namespace {

std::string human_bytes(double b) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (b >= 1024.0 && u < 4) {
        b /= 1024.0;
        ++u;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.2f %s", b, units[u]);
    return buf;
}

std::string stamp(std::uint64_t ns) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%llu.%09llu",
                  static_cast<unsigned long long>(ns / 1000000000ull),
                  static_cast<unsigned long long>(ns % 1000000000ull));
    return buf;
}

}  // namespace

McapInfo info(const std::string& path) {
    McapReader reader(path);
    McapInfo r;
    r.path = path;
    r.file_size = reader.file_size();
    r.profile = reader.header().profile;
    r.library = reader.header().library;
    r.indexed = reader.indexed();
    r.complete = reader.complete();
    r.problems = reader.problems();
    const Statistics& st = reader.statistics();
    r.messages = st.message_count;
    r.start_time = st.message_start_time;
    r.end_time = st.message_end_time;
    r.duration_s = st.message_count ? static_cast<double>(r.end_time - r.start_time) * 1e-9 : 0.0;
    for (const auto& c : reader.chunks()) {
        if (c.loose_messages) continue;
        ++r.chunks;
        ++r.chunks_by_compression[c.compression];
        r.compressed_bytes += c.compressed_size;
        r.uncompressed_bytes += c.uncompressed_size;
    }
    for (const auto& [id, ch] : reader.channels()) {
        TopicInfo t;
        t.channel_id = id;
        t.topic = ch.topic;
        t.message_encoding = ch.message_encoding;
        const auto sc = reader.schemas().find(ch.schema_id);
        if (sc != reader.schemas().end()) {
            t.type = sc->second.name;
            t.schema_encoding = sc->second.encoding;
        }
        const auto n = st.channel_message_counts.find(id);
        t.messages = n == st.channel_message_counts.end() ? 0 : n->second;
        t.rate_hz = r.duration_s > 0.0 ? static_cast<double>(t.messages) / r.duration_s : 0.0;
        r.topics.push_back(std::move(t));
    }
    std::sort(r.topics.begin(), r.topics.end(), [](const TopicInfo& a, const TopicInfo& b) {
        return a.topic != b.topic ? a.topic < b.topic : a.channel_id < b.channel_id;
    });
    return r;
}

void print_info(const McapInfo& in, std::ostream& out) {
    out << "file:      " << in.path << "\n";
    out << "size:      " << human_bytes(static_cast<double>(in.file_size)) << " (" << in.file_size
        << " bytes)\n";
    out << "library:   " << (in.library.empty() ? "-" : in.library)
        << "   profile: " << (in.profile.empty() ? "-" : in.profile) << "\n";
    if (in.problems.empty()) {
        out << "state:     complete, " << (in.indexed ? "indexed" : "not indexed (linear scan)")
            << "\n";
    } else {
        out << "state:     " << in.problems.front() << "\n";
        if (in.problems.size() > 1) {
            out << "           (+" << in.problems.size() - 1 << " more problem(s))\n";
        }
    }
    out << "messages:  " << in.messages << "\n";
    char buf[1024];
    std::snprintf(buf, sizeof buf, "%.3f s (%s .. %s)", in.duration_s, stamp(in.start_time).c_str(),
                  stamp(in.end_time).c_str());
    out << "duration:  " << buf << "\n";
    out << "chunks:    " << in.chunks;
    if (!in.chunks_by_compression.empty()) {
        out << " (";
        bool first = true;
        for (const auto& [name, n] : in.chunks_by_compression) {
            out << (first ? "" : ", ") << (name.empty() ? "none" : name) << ": " << n;
            first = false;
        }
        out << ")";
    }
    if (in.uncompressed_bytes > 0) {
        std::snprintf(buf, sizeof buf, ", %s -> %s (%.1f%%)",
                      human_bytes(static_cast<double>(in.uncompressed_bytes)).c_str(),
                      human_bytes(static_cast<double>(in.compressed_bytes)).c_str(),
                      100.0 * static_cast<double>(in.compressed_bytes) /
                          static_cast<double>(in.uncompressed_bytes));
        out << buf;
    }
    out << "\n";
    out << "topics:    " << in.topics.size() << "\n";
    std::size_t w_topic = 5, w_type = 4;
    for (const auto& t : in.topics) {
        w_topic = std::max(w_topic, t.topic.size());
        w_type = std::max(w_type, t.type.size());
    }
    for (const auto& t : in.topics) {
        std::snprintf(buf, sizeof buf, "  %-*s  %-*s  %8llu msgs  %8.2f Hz  [%s/%s]",
                      static_cast<int>(w_topic), t.topic.c_str(), static_cast<int>(w_type),
                      t.type.empty() ? "-" : t.type.c_str(),
                      static_cast<unsigned long long>(t.messages), t.rate_hz,
                      t.schema_encoding.empty() ? "-" : t.schema_encoding.c_str(),
                      t.message_encoding.c_str());
        out << buf << "\n";
    }
}

}  // namespace ltm::recorder
