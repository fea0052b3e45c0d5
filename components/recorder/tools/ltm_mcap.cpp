// ltm_mcap: MCAP files of ltm recordings, without DDS.
//   ltm_mcap info FILE
//   ltm_mcap verify FILE
//   ltm_mcap recover IN -o OUT [--compression zstd|lz4|none]
//   ltm_mcap manifest FILE [-o OUT.json]
//   ltm_mcap write-test-file OUT [--manifest M.json] [--compression C] [--chunk-size BYTES]
//                            [--messages N]
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"
#include "recorder/core/mcap_info.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/mcap_recover.hpp"
#include "recorder/tools/manifest.hpp"

namespace {

using namespace ltm::recorder;

int usage() {
    std::cerr << "usage: ltm_mcap info FILE\n"
                 "       ltm_mcap verify FILE\n"
                 "       ltm_mcap recover IN -o OUT [--compression zstd|lz4|none]\n"
                 "       ltm_mcap manifest FILE [-o OUT.json]\n"
                 "       ltm_mcap write-test-file OUT [--manifest M.json] [--compression C]\n"
                 "                                [--chunk-size BYTES] [--messages N]\n";
    return 2;
}

struct Args {
    std::vector<std::string> positional;
    std::string out, manifest, compression;
    std::size_t chunk_size = 0, messages = 0;
};

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 2; i < argc; ++i) {
        const std::string k = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(k + " needs a value");
            return argv[++i];
        };
        if (k == "-o" || k == "--output")
            a.out = value();
        else if (k == "--manifest")
            a.manifest = value();
        else if (k == "--compression")
            a.compression = value();
        else if (k == "--chunk-size")
            a.chunk_size = std::stoul(value());
        else if (k == "--messages")
            a.messages = std::stoul(value());
        else if (!k.empty() && k[0] == '-')
            throw std::invalid_argument("unknown option " + k);
        else
            a.positional.push_back(k);
    }
    return a;
}

Compression compression_arg(const std::string& text) {
    Compression c = Compression::kZstd;
    if (!text.empty() && !parse_compression(text, c)) {
        throw std::invalid_argument("--compression must be zstd, lz4 or none, not '" + text + "'");
    }
    return c;
}

int cmd_info(const Args& a) {
    if (a.positional.size() != 1) return usage();
    const McapInfo in = info(a.positional[0]);
    print_info(in, std::cout);
    if (!in.problems.empty()) {
        std::cerr << a.positional[0] << ": " << in.problems.front() << "\n";
    }
    return 0;
}

int cmd_verify(const Args& a) {
    if (a.positional.size() != 1) return usage();
    McapReader reader(a.positional[0]);
    const VerifyReport rep = reader.verify();
    if (rep.ok) {
        std::cout << a.positional[0] << ": OK (" << rep.messages << " messages in " << rep.chunks
                  << " chunks; CRCs, message indexes and summary checked)\n";
        return 0;
    }
    for (const auto& p : rep.problems) std::cout << a.positional[0] << ": " << p << "\n";
    return 1;
}

int cmd_recover(const Args& a) {
    if (a.positional.size() != 1 || a.out.empty()) return usage();
    McapWriterConfig config;
    config.compression = compression_arg(a.compression);
    const RecoverResult r = recover(a.positional[0], a.out, config, a.compression.empty());
    if (!r.problems.empty()) std::cerr << a.positional[0] << ": " << r.problems.front() << "\n";
    std::cout << "recovered " << r.messages << " messages in " << r.chunks << " chunks into "
              << a.out << "\n";
    return 0;
}

int cmd_manifest(const Args& a) {
    if (a.positional.size() != 1) return usage();
    McapReader reader(a.positional[0]);
    if (a.out.empty()) {
        tools::write_manifest(reader, std::cout);
    } else {
        std::ofstream f(a.out);
        if (!f) throw ltm::common::IoError(a.out, "cannot write");
        tools::write_manifest(reader, f);
    }
    for (const auto& p : reader.problems()) std::cerr << a.positional[0] << ": " << p << "\n";
    return reader.problems().empty() ? 0 : 1;
}

int cmd_write_test_file(const Args& a) {
    if (a.positional.size() != 1) return usage();
    tools::TestFileOptions o;
    o.compression = compression_arg(a.compression);
    if (a.chunk_size) o.chunk_size = a.chunk_size;
    if (a.messages) o.messages = a.messages;
    if (a.manifest.empty()) {
        std::ofstream devnull("/dev/null");
        tools::write_test_file(a.positional[0], o, devnull);
    } else {
        std::ofstream f(a.manifest);
        if (!f) throw ltm::common::IoError(a.manifest, "cannot write");
        tools::write_test_file(a.positional[0], o, f);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    const std::string cmd = argv[1];
    try {
        const Args a = parse(argc, argv);
        if (cmd == "info") return cmd_info(a);
        if (cmd == "verify") return cmd_verify(a);
        if (cmd == "recover") return cmd_recover(a);
        if (cmd == "manifest") return cmd_manifest(a);
        if (cmd == "write-test-file") return cmd_write_test_file(a);
        std::cerr << "ltm_mcap: unknown command '" << cmd << "'\n";
        return usage();
    } catch (const std::exception& e) {
        std::cerr << "ltm_mcap " << cmd << ": " << e.what() << "\n";
        return 1;
    }
}
