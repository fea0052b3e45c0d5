// ltm_host: composes the components of a launch config into one process.
#include <cstdio>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "runtime/config_error.hpp"
#include "runtime/dds_error.hpp"
#include "runtime/host.hpp"
#include "runtime/messages.hpp"
#include "runtime/registry.hpp"

int main(int argc, char** argv) {
    using namespace ltm::runtime;
    namespace cli = ltm::common::cli;
    block_stop_signals();
    tune_malloc_for_large_samples();

    std::string launch, log_level = "info";
    std::vector<std::string> overrides;
    bool check_only = false, list_components = false, list_types = false;
    CLI::App app{"Composes the components of a launch config into one process", "ltm_host"};
    cli::configure(app);
    app.add_option("LAUNCH", launch, "the launch config (YAML)");
    app.add_option("--set", overrides,
                   "NAME.KEY=VALUE: override parameter KEY of component NAME (or a top-level "
                   "KEY=VALUE); repeatable")
        ->allow_extra_args(false)
        ->default_str("");
    app.add_flag("--check", check_only,
                 "configure every component, then exit (validates the config)");
    app.add_option("--log-level", log_level, "least severe message logged")
        ->check(cli::one_of({"debug", "info", "warn", "error"}));
    app.add_flag("--list-components", list_components, "the component types, then exit");
    app.add_flag("--list-types", list_types, "the message types (ROS and DDS names), then exit");
    if (const int code = cli::parse(app, argc, argv); code >= 0) return code;

    if (list_components) {
        for (const auto* info : ComponentRegistry::instance().all())
            std::printf("%-22s %s\n", info->type.c_str(), info->description.c_str());
        return 0;
    }
    if (list_types) {
        for (const auto& t : known_message_types())
            std::printf("%-36s %s\n", t.ros_name.c_str(), t.dds_name.c_str());
        return 0;
    }
    if (launch.empty())
        return cli::usage_error(app, cli::UsageError("LAUNCH", "is required (a launch config)"));
    set_log_level(log_level == "debug"   ? LogLevel::kDebug
                  : log_level == "warn"  ? LogLevel::kWarn
                  : log_level == "error" ? LogLevel::kError
                                         : LogLevel::kInfo);
    try {
        Host host(load_launch_config(launch, overrides));
        if (check_only) {
            std::printf("%s: %zu components configured in %.0f ms\n", launch.c_str(),
                        host.component_count(), host.startup_ms());
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
