#include "common/cli/cli.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace ltm::common::cli {
namespace {

// A tool with one of each kind of option and a subcommand.
struct Tool {
    CLI::App app{"a test tool", "tool"};
    int seed = 3;
    std::size_t count = 0;
    double radius = 5.0;
    std::string format = "kitti", input;
    std::vector<std::string> sets;
    bool quiet = false;
    long delta = 1;
    CLI::App* sub = nullptr;

    Tool() {
        configure(app);
        app.add_option("INPUT", input, "the input file");
        app.add_option("--seed", seed, "random seed");
        app.add_option("--count", count, "how many");
        app.add_option("--radius", radius, "search radius [m]")->check(positive());
        app.add_option("--format", format, "file format")->check(one_of({"kitti", "tum"}));
        app.add_option("--set", sets, "overrides");
        app.add_flag("--quiet", quiet, "no progress");
        sub = app.add_subcommand("sub", "a subcommand");
        sub->add_option("--delta", delta, "frame delta")->check(at_least(1));
    }
};

struct Outcome {
    int code;
    std::string out, err;
};

Outcome run(Tool& t, const std::vector<std::string>& args) {
    std::ostringstream out, err;
    const int code = parse(t.app, args, out, err);
    return {code, out.str(), err.str()};
}

Outcome run(const std::vector<std::string>& args) {
    Tool t;
    return run(t, args);
}

TEST(Cli, ParsesTypedOptionsAndKeepsDefaults) {
    Tool t;
    const Outcome o = run(t, {"in.txt", "--seed", "-4", "--count=7", "--set", "a=1", "--set=b=2",
                              "--quiet", "--format", "tum"});
    ASSERT_EQ(o.code, -1) << o.err;
    EXPECT_EQ(t.input, "in.txt");
    EXPECT_EQ(t.seed, -4);
    EXPECT_EQ(t.count, 7u);
    EXPECT_EQ(t.radius, 5.0);
    EXPECT_EQ(t.sets, (std::vector<std::string>{"a=1", "b=2"}));
    EXPECT_TRUE(t.quiet);
    EXPECT_EQ(t.format, "tum");
}

TEST(Cli, EveryUsageErrorIsOneLineWithExitCode2) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--bogus"}, "tool: --bogus: unknown option\n"},
        {{"--bogus=1", "--seed", "x"}, "tool: --bogus: unknown option\n"},
        {{"in", "--seed"}, "tool: --seed: needs a value\n"},
        {{"in", "--seed", "x"}, "tool: --seed: expected an integer, got 'x'\n"},
        {{"--count", "-2"}, "tool: --count: expected a non-negative integer, got '-2'\n"},
        {{"--radius", "1e"}, "tool: --radius: expected a number, got '1e'\n"},
        {{"--radius", "0"}, "tool: --radius: must be positive, not 0\n"},
        {{"--format", "ply"}, "tool: --format: must be kitti|tum, not 'ply'\n"},
        {{"--quiet=1"}, "tool: --quiet: takes no value\n"},
        {{"a", "b"}, "tool: b: unexpected argument\n"},
        {{"sub", "--delta", "0"}, "tool sub: --delta: must be at least 1, not 0\n"},
        {{"sub", "--delta"}, "tool sub: --delta: needs a value\n"},
        {{"sub", "--nope", "--delta", "q"}, "tool sub: --nope: unknown option\n"},
    };
    for (const auto& [args, line] : cases) {
        const Outcome o = run(args);
        EXPECT_EQ(o.code, 2) << line;
        EXPECT_EQ(o.err, line);
        EXPECT_EQ(o.out, "");
    }
}

TEST(Cli, HelpListsTheDeclaredOptionsAndWins) {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"--help"}, {"-h"}, {"--seed", "x", "--help"}, {"--bogus", "-h"}}) {
        const Outcome o = run(args);
        EXPECT_EQ(o.code, 0);
        EXPECT_EQ(o.err, "");
        for (const char* s : {"a test tool", "--seed INT", "--seed INT=3", "--radius", "--format",
                              "{kitti,tum}", "--quiet", "INPUT", "sub"})
            EXPECT_NE(o.out.find(s), std::string::npos) << s << " in\n" << o.out;
    }
    const Outcome sub = run({"sub", "--help"});
    EXPECT_EQ(sub.code, 0);
    EXPECT_NE(sub.out.find("tool sub"), std::string::npos) << sub.out;
    EXPECT_NE(sub.out.find("--delta"), std::string::npos) << sub.out;
}

TEST(Cli, RequiredOptionsAndCommands) {
    CLI::App app{"x", "tool"};
    configure(app);
    std::string out;
    app.add_option("--out", out, "output")->required();
    app.add_subcommand("run", "run it");
    app.add_subcommand("list", "list them");
    app.require_subcommand(1);
    std::ostringstream o, e;
    EXPECT_EQ(parse(app, {"--out", "d"}, o, e), 2);
    EXPECT_EQ(e.str(), "tool: a command is required (run, list)\n");
    CLI::App app2{"x", "tool"};
    configure(app2);
    app2.add_option("--out", out, "output")->required();
    app2.add_subcommand("run", "run it");
    std::ostringstream o2, e2;
    EXPECT_EQ(parse(app2, {"walk"}, o2, e2), 2);
    EXPECT_EQ(e2.str(), "tool: walk: unknown command (run)\n");
    CLI::App app3{"x", "tool"};
    configure(app3);
    app3.add_option("--out", out, "output")->required();
    std::ostringstream o3, e3;
    EXPECT_EQ(parse(app3, {}, o3, e3), 2);
    EXPECT_EQ(e3.str(), "tool: --out: is required\n");
}

TEST(Cli, UsageErrorsAfterParsingNameTheCommand) {
    Tool t;
    ASSERT_EQ(run(t, {"sub", "--delta", "2"}).code, -1);
    std::ostringstream err;
    EXPECT_EQ(usage_error(t.app, UsageError("--delta", "too large for this run"), err), 2);
    EXPECT_EQ(err.str(), "tool sub: --delta: too large for this run\n");
}

}  // namespace
}  // namespace ltm::common::cli
