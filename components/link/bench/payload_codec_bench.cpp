// ltm_bench_payload_codec: what the link's payload codec makes of recorded messages.
//   ltm_bench_payload_codec RECORDING.mcap [--level N] [--km KM] [--repeat R]
// For each topic of the recording (local maps split into snapshots and finished maps): messages,
// CDR bytes, bytes with plain zstd at the same level, bytes with the codec (and which codec each
// message got), encode and decode MB/s of the codec (CDR bytes per second, one thread, best of R
// passes), and every message decoded back byte for byte. --km: the distance the recording covers,
// for MB per km.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "common/core/cdr_cursor.hpp"
#include "link/core/payload_codec.hpp"
#include "recorder/core/mcap_reader.hpp"

using namespace ltm;
using Clock = std::chrono::steady_clock;

namespace {

struct Row {
    std::size_t messages = 0;
    double cdr = 0, zstd = 0, codec = 0;  // bytes
    double encode_s = 0, decode_s = 0;
    std::map<std::string, std::size_t> codecs;
    std::size_t mismatches = 0;
};

// "ltm_msgs/msg/Keyframe" -> "ltm_msgs::msg::dds_::Keyframe_" (the DDS type the uplink names).
std::string dds_type(const std::string& ros) {
    const std::size_t a = ros.find('/'), b = ros.rfind('/');
    if (a == std::string::npos || a == b) return ros;
    return ros.substr(0, a) + "::" + ros.substr(a + 1, b - a - 1) + "::dds_::" + ros.substr(b + 1) +
           "_";
}

// A LocalMap_'s `finished` flag (false when it does not parse).
bool finished_map(const std::vector<std::uint8_t>& cdr) {
    if (!common::is_cdr_le(cdr)) return false;
    common::CdrReader r(cdr.data(), cdr.size());
    std::int32_t sec;
    std::uint32_t nsec, revision;
    std::uint64_t id;
    std::uint8_t finished = 0;
    return r.read(sec) && r.read(nsec) && r.skip_string() && r.read(id) && r.read(revision) &&
           r.read(finished) && finished != 0;
}

double seconds_since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

int usage() {
    std::fprintf(stderr,
                 "usage: ltm_bench_payload_codec RECORDING.mcap [--level N] [--km KM] "
                 "[--repeat R]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    std::string file;
    link::PayloadCodecConfig config;
    double km = 0;
    int repeat = 1;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if ((a == "--level" || a == "--km" || a == "--repeat") && i + 1 < argc) {
                const std::string v = argv[++i];
                if (a == "--level") config.level = std::stoi(v);
                if (a == "--km") km = std::stod(v);
                if (a == "--repeat") repeat = std::max(1, std::stoi(v));
            } else if (a.rfind("--", 0) != 0 && file.empty()) {
                file = a;
            } else {
                return usage();
            }
        }
    } catch (const std::exception&) {
        return usage();
    }
    try {
        recorder::McapReader reader(file);
        if (!reader.problem().empty()) std::fprintf(stderr, "%s\n", reader.problem().c_str());
        std::map<std::string, Row> rows;
        auto cursor = reader.messages();
        for (recorder::MessageView m; cursor.next(m);) {
            const std::string type = m.schema ? dds_type(m.schema->name) : "";
            const std::vector<std::uint8_t> cdr(m.data, m.data + m.size);
            std::string topic = m.channel->topic;
            if (topic.rfind("rt/", 0) == 0) topic = topic.substr(2);
            if (type == "ltm_msgs::msg::dds_::LocalMap_")
                topic += finished_map(cdr) ? " (finished)" : " (snapshots)";
            Row& row = rows[topic];
            ++row.messages;
            row.cdr += static_cast<double>(cdr.size());
            // Plain zstd at the same level: the codec given a type it has no transform for.
            row.zstd += static_cast<double>(encode_payload("plain", cdr, config).size());
            std::vector<std::uint8_t> wire, back;
            double best_encode = 1e9, best_decode = 1e9;
            for (int r = 0; r < repeat; ++r) {
                Clock::time_point t = Clock::now();
                wire = link::encode_payload(type, cdr, config);
                best_encode = std::min(best_encode, seconds_since(t));
                t = Clock::now();
                back = link::decode_payload(type, wire);
                best_decode = std::min(best_decode, seconds_since(t));
            }
            row.encode_s += best_encode;
            row.decode_s += best_decode;
            row.codec += static_cast<double>(wire.size());
            ++row.codecs[link::codec_name(link::payload_codec(wire))];
            if (back != cdr) ++row.mismatches;
        }
        std::printf("%s: zstd level %d%s\n", file.c_str(), config.level,
                    km > 0 ? (", " + std::to_string(km) + " km").c_str() : "");
        std::printf("%-28s %6s %10s %10s %6s %10s %6s %9s %9s  %s\n", "topic", "msgs", "CDR MB",
                    "zstd MB", "ratio", "codec MB", "ratio", "enc MB/s", "dec MB/s", "codecs");
        Row total;
        std::size_t mismatches = 0;
        for (const auto& [topic, r] : rows) {
            std::string codecs;
            for (const auto& [name, n] : r.codecs)
                codecs += (codecs.empty() ? "" : ", ") + name + " " + std::to_string(n);
            std::printf("%-28s %6zu %10.2f %10.2f %6.2f %10.2f %6.2f %9.0f %9.0f  %s\n",
                        topic.c_str(), r.messages, r.cdr / 1e6, r.zstd / 1e6, r.cdr / r.zstd,
                        r.codec / 1e6, r.cdr / r.codec, r.cdr / 1e6 / r.encode_s,
                        r.cdr / 1e6 / r.decode_s, codecs.c_str());
            total.messages += r.messages;
            total.cdr += r.cdr;
            total.zstd += r.zstd;
            total.codec += r.codec;
            total.encode_s += r.encode_s;
            total.decode_s += r.decode_s;
            mismatches += r.mismatches;
        }
        std::printf("%-28s %6zu %10.2f %10.2f %6.2f %10.2f %6.2f %9.0f %9.0f\n", "all",
                    total.messages, total.cdr / 1e6, total.zstd / 1e6, total.cdr / total.zstd,
                    total.codec / 1e6, total.cdr / total.codec, total.cdr / 1e6 / total.encode_s,
                    total.cdr / 1e6 / total.decode_s);
        if (km > 0)
            for (const auto& [topic, r] : rows)
                std::printf("per km: %-28s CDR %8.1f MB, zstd %8.1f MB, codec %8.1f MB\n",
                            topic.c_str(), r.cdr / 1e6 / km, r.zstd / 1e6 / km, r.codec / 1e6 / km);
        if (mismatches > 0) {
            std::fprintf(stderr, "%zu messages did not decode to their CDR\n", mismatches);
            return 1;
        }
        std::printf("every message decoded back byte for byte\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_bench_payload_codec: %s\n", e.what());
        return 1;
    }
    return 0;
}
