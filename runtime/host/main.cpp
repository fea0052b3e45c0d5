// ltm_host: composes the components of a launch config into one process.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "runtime/config_error.hpp"
#include "runtime/dds_error.hpp"
#include "runtime/host.hpp"
#include "runtime/messages.hpp"
#include "runtime/registry.hpp"

namespace {

void usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: ltm_host LAUNCH.yaml [--set NAME.KEY=VALUE ...] [--check] [--log-level LEVEL]\n"
                 "       ltm_host --list-components | --list-types\n"
                 "  --set NAME.KEY=VALUE  override parameter KEY of component NAME (or a top-level KEY=VALUE)\n"
                 "  --check               configure every component, then exit (validates the config)\n"
                 "  --log-level LEVEL     debug, info (default), warn or error\n");
}

}  // namespace

int main(int argc, char** argv) {
    using namespace ltm::runtime;
    block_stop_signals();
    tune_malloc_for_large_samples();

    std::string launch;
    std::vector<std::string> overrides;
    bool check_only = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            usage(stdout);
            return 0;
        } else if (a == "--list-components") {
            for (const auto* info : ComponentRegistry::instance().all())
                std::printf("%-22s %s\n", info->type.c_str(), info->description.c_str());
            return 0;
        } else if (a == "--list-types") {
            for (const auto& t : known_message_types())
                std::printf("%-36s %s\n", t.ros_name.c_str(), t.dds_name.c_str());
            return 0;
        } else if (a == "--set" && i + 1 < argc) {
            overrides.push_back(argv[++i]);
        } else if (a.rfind("--set=", 0) == 0) {
            overrides.push_back(a.substr(6));
        } else if (a == "--check") {
            check_only = true;
        } else if (a == "--log-level" && i + 1 < argc) {
            const std::string l = argv[++i];
            if (l == "debug") set_log_level(LogLevel::kDebug);
            else if (l == "info") set_log_level(LogLevel::kInfo);
            else if (l == "warn") set_log_level(LogLevel::kWarn);
            else if (l == "error") set_log_level(LogLevel::kError);
            else {
                std::fprintf(stderr, "ltm_host: --log-level: expected debug, info, warn or error\n");
                return 2;
            }
        } else if (!a.empty() && a[0] != '-' && launch.empty()) {
            launch = a;
        } else {
            std::fprintf(stderr, "ltm_host: unknown argument '%s'\n", a.c_str());
            usage(stderr);
            return 2;
        }
    }
    if (launch.empty()) {
        usage(stderr);
        return 2;
    }
    try {
        Host host(load_launch_config(launch, overrides));
        if (check_only) {
            std::printf("%s: %zu components configured in %.0f ms\n", launch.c_str(), host.component_count(),
                        host.startup_ms());
            return 0;
        }
        return host.run();
    } catch (const ConfigError& e) {
        std::fprintf(stderr, "ltm_host: %s\n", e.what());
        return 2;
    } catch (const DdsError& e) {
        std::fprintf(stderr, "ltm_host: DDS: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_host: %s\n", e.what());
        return 2;
    }
}
