// ltm_mcap: MCAP files of ltm recordings, without DDS: info, verify, recover, manifest,
// write-test-file (`ltm_mcap --help`, `ltm_mcap COMMAND --help`).
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "recorder/core/mcap_info.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/mcap_recover.hpp"
#include "recorder/tools/manifest.hpp"

namespace {

using namespace ltm::recorder;
namespace cli = ltm::common::cli;

struct Args {
    std::string file, out, manifest, compression;
    std::size_t chunk_size = 0, messages = 0;
};

// --compression, already checked to be zstd, lz4 or none (zstd when absent).
Compression compression_arg(const std::string& text) {
    Compression c = Compression::kZstd;
    if (!text.empty()) parse_compression(text, c);
    return c;
}

int cmd_info(const Args& a) {
    const McapInfo in = info(a.file);
    print_info(in, std::cout);
    if (!in.problems.empty()) {
        std::cerr << a.file << ": " << in.problems.front() << "\n";
    }
    return 0;
}

int cmd_verify(const Args& a) {
    McapReader reader(a.file);
    const VerifyReport rep = reader.verify();
    if (rep.ok) {
        std::cout << a.file << ": OK (" << rep.messages << " messages in " << rep.chunks
                  << " chunks; CRCs, message indexes and summary checked)\n";
        return 0;
    }
    for (const auto& p : rep.problems) std::cout << a.file << ": " << p << "\n";
    return 1;
}

int cmd_recover(const Args& a) {
    McapWriterConfig config;
    config.compression = compression_arg(a.compression);
    const RecoverResult r = recover(a.file, a.out, config, a.compression.empty());
    if (!r.problems.empty()) std::cerr << a.file << ": " << r.problems.front() << "\n";
    std::cout << "recovered " << r.messages << " messages in " << r.chunks << " chunks into "
              << a.out << "\n";
    return 0;
}

int cmd_manifest(const Args& a) {
    McapReader reader(a.file);
    if (a.out.empty()) {
        tools::write_manifest(reader, std::cout);
    } else {
        std::ofstream f(a.out);
        if (!f) throw ltm::common::IoError(a.out, "cannot write");
        tools::write_manifest(reader, f);
    }
    for (const auto& p : reader.problems()) std::cerr << a.file << ": " << p << "\n";
    return reader.problems().empty() ? 0 : 1;
}

int cmd_write_test_file(const Args& a) {
    tools::TestFileOptions o;
    o.compression = compression_arg(a.compression);
    if (a.chunk_size) o.chunk_size = a.chunk_size;
    if (a.messages) o.messages = a.messages;
    if (a.manifest.empty()) {
        std::ofstream devnull("/dev/null");
        tools::write_test_file(a.file, o, devnull);
    } else {
        std::ofstream f(a.manifest);
        if (!f) throw ltm::common::IoError(a.manifest, "cannot write");
        tools::write_test_file(a.file, o, f);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"MCAP files of ltm recordings, without DDS", "ltm_mcap"};
    cli::configure(app);
    app.require_subcommand(1);
    Args a;
    const std::string compression_help = "chunk compression (default zstd)";
    const auto file = [&](CLI::App* c, const char* name, const char* help) {
        c->add_option(name, a.file, help)->required();
        return c;
    };
    file(app.add_subcommand("info", "summary: channels, messages, chunks, time range"), "FILE",
         "the recording");
    file(app.add_subcommand("verify", "check CRCs, message indexes and the summary"), "FILE",
         "the recording");
    CLI::App* recover =
        file(app.add_subcommand("recover",
                                "copy every readable message of a damaged file into a new one"),
             "IN", "the damaged recording");
    recover->add_option("-o,--output", a.out, "the recovered file")->required();
    recover->add_option("--compression", a.compression, compression_help)
        ->check(cli::one_of({"zstd", "lz4", "none"}));
    CLI::App* manifest =
        file(app.add_subcommand("manifest", "JSON manifest of every message (channel, times, CRC)"),
             "FILE", "the recording");
    manifest->add_option("-o,--output", a.out, "write it here instead of to stdout");
    CLI::App* test_file = file(
        app.add_subcommand("write-test-file", "a deterministic file for interoperability tests"),
        "OUT", "the file to write");
    test_file->add_option("--manifest", a.manifest, "write the manifest of what it wrote here");
    test_file->add_option("--compression", a.compression, compression_help)
        ->check(cli::one_of({"zstd", "lz4", "none"}));
    test_file->add_option("--chunk-size", a.chunk_size, "chunk size [bytes] (0: 65536)");
    test_file->add_option("--messages", a.messages, "messages to write (0: 600)");
    if (const int code = cli::parse(app, argc, argv); code >= 0) return code;

    const std::string cmd = app.get_subcommands().front()->get_name();
    try {
        if (cmd == "info") return cmd_info(a);
        if (cmd == "verify") return cmd_verify(a);
        if (cmd == "recover") return cmd_recover(a);
        if (cmd == "manifest") return cmd_manifest(a);
        return cmd_write_test_file(a);
    } catch (const std::exception& e) {
        std::cerr << "ltm_mcap " << cmd << ": " << e.what() << "\n";
        return 1;
    }
}
