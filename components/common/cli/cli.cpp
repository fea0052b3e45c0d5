#include "common/cli/cli.hpp"

#include <cstdlib>
#include <iostream>
#include <regex>

namespace ltm::common::cli {
namespace {

const CLI::App* selected(const CLI::App& app) {
    const CLI::App* a = &app;
    while (!a->get_subcommands().empty()) a = a->get_subcommands().front();
    return a;
}

bool help_asked(const CLI::App& app) {
    for (const CLI::App* a = selected(app); a != nullptr; a = a->get_parent())
        if (a->get_help_ptr() != nullptr && a->get_help_ptr()->count() > 0) return true;
    return false;
}

// The option `name` of the selected command or of a command above it.
const CLI::Option* find_option(const CLI::App& app, const std::string& name) {
    for (const CLI::App* a = selected(app); a != nullptr; a = a->get_parent())
        if (const CLI::Option* o = a->get_option_no_throw(name)) return o;
    return nullptr;
}

std::string expected_value(const CLI::Option* option) {
    const std::string type = option == nullptr ? "" : option->get_type_name();
    if (type.rfind("UINT", 0) == 0) return "a non-negative integer";
    if (type.rfind("INT", 0) == 0) return "an integer";
    if (type.rfind("FLOAT", 0) == 0) return "a number";
    return "a valid value";
}

std::string command_list(const CLI::App& app) {
    std::string list;
    for (const CLI::App* sub : app.get_subcommands({}))
        list += (list.empty() ? "" : ", ") + sub->get_name();
    return list;
}

// `--flag: problem` for a CLI11 parse error.
std::string describe(const CLI::App& app, const CLI::ParseError& e) {
    const std::string what = e.what();
    std::smatch m;
    // Anything left unparsed: an unknown option names itself before whatever it caused.
    const std::vector<std::string> left = app.remaining(true);
    for (const std::string& arg : left)
        if (arg.size() > 1 && arg[0] == '-')
            return arg.substr(0, arg.find('=')) + ": unknown option";
    const CLI::App* sel = selected(app);
    if (!left.empty() && (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr ||
                          dynamic_cast<const CLI::RequiredError*>(&e) != nullptr)) {
        const bool takes_positionals =
            !app.get_options([](const CLI::Option* o) { return o->get_positional(); }).empty();
        if (sel == &app && !app.get_subcommands({}).empty() && !takes_positionals)
            return left.front() + ": unknown command (" + command_list(app) + ")";
        return left.front() + ": unexpected argument";
    }
    if (dynamic_cast<const CLI::ConversionError*>(&e) != nullptr &&
        std::regex_match(what, m, std::regex("Could not convert: (\\S+) = (.*)"))) {
        return m[1].str() + ": expected " + expected_value(find_option(app, m[1].str())) +
               ", got '" + m[2].str() + "'";
    }
    if (std::regex_match(what, m, std::regex("(\\S+): \\d+ required .* missing")))
        return m[1].str() + ": needs a value";
    if (std::regex_match(what, m, std::regex("(\\S+) was given a disallowed flag override")))
        return (m[1].str()[0] == '-' ? "" : "--") + m[1].str() + ": takes no value";
    if (what == "A subcommand is required")
        return "a command is required (" + command_list(*sel) + ")";
    if (std::regex_match(what, m, std::regex("(\\S+) is required")))
        return m[1].str() + ": is required";
    if (std::regex_match(what, m, std::regex("(\\S+) requires (\\S+)")))
        return m[1].str() + ": needs " + m[2].str();
    if (std::regex_match(what, m, std::regex("(\\S+) excludes (\\S+)")))
        return m[1].str() + ": cannot go with " + m[2].str();
    return what;
}

// CLI11 converts "-2" to a huge unsigned number: every unsigned option refuses a sign.
void refuse_negative_unsigned(CLI::App& app) {
    for (CLI::Option* o : app.get_options()) {
        if (o->get_type_name().rfind("UINT", 0) != 0) continue;
        try {
            o->get_validator("non-negative");
            continue;  // already there (parsed before)
        } catch (const CLI::OptionNotFound&) {
        }
        o->check(CLI::Validator(
            [](std::string& value) -> std::string {
                if (value.empty() || value[0] != '-') return "";
                return "expected a non-negative integer, got '" + value + "'";
            },
            "", "non-negative"));
    }
    for (CLI::App* sub : app.get_subcommands({})) refuse_negative_unsigned(*sub);
}

}  // namespace

UsageError::UsageError(const std::string& flag, const std::string& problem)
    : std::runtime_error(flag + ": " + problem) {}

UsageError::UsageError(const std::string& problem) : std::runtime_error(problem) {}

void configure(CLI::App& app) {
    app.option_defaults()->always_capture_default()->disable_flag_override();
    app.get_formatter()->column_width(32);
}

std::string tool_name(const CLI::App& app) {
    std::string name = app.get_name();
    for (const CLI::App* a = &app; !a->get_subcommands().empty();) {
        a = a->get_subcommands().front();
        name += " " + a->get_name();
    }
    return name;
}

int parse(CLI::App& app, const std::vector<std::string>& args, std::ostream& out,
          std::ostream& err) {
    refuse_negative_unsigned(app);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
    try {
        app.parse(reversed);
        return -1;
    } catch (const CLI::CallForAllHelp&) {
        out << app.help("", CLI::AppFormatMode::All);
        return 0;
    } catch (const CLI::ParseError& e) {
        // --help anywhere wins over whatever else is wrong on the line.
        if (dynamic_cast<const CLI::CallForHelp*>(&e) != nullptr || help_asked(app)) {
            out << app.help();
            return 0;
        }
        err << tool_name(app) << ": " << describe(app, e) << "\n";
        return 2;
    }
}

int parse(CLI::App& app, int argc, const char* const* argv) {
    return parse(app, std::vector<std::string>(argv + std::min(argc, 1), argv + argc), std::cout,
                 std::cerr);
}

int usage_error(const CLI::App& app, const UsageError& e, std::ostream& err) {
    err << tool_name(app) << ": " << e.what() << "\n";
    return 2;
}

int usage_error(const CLI::App& app, const UsageError& e) { return usage_error(app, e, std::cerr); }

CLI::Validator one_of(const std::vector<std::string>& choices) {
    std::string list, shown;
    for (const auto& c : choices) {
        list += (list.empty() ? "" : "|") + c;
        shown += (shown.empty() ? "" : ",") + c;
    }
    return CLI::Validator(
        [choices, list](std::string& value) -> std::string {
            for (const auto& c : choices)
                if (c == value) return "";
            return "must be " + list + ", not '" + value + "'";
        },
        "{" + shown + "}");
}

CLI::Validator at_least(double minimum) {
    std::ostringstream text;
    text << minimum;
    const std::string shown = text.str();
    return CLI::Validator(
        [minimum, shown](std::string& value) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0') return "";  // not a number: the conversion says so
            return v >= minimum ? "" : "must be at least " + shown + ", not " + value;
        },
        "");
}

CLI::Validator positive() {
    return CLI::Validator(
        [](std::string& value) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0') return "";
            return v > 0.0 ? "" : "must be positive, not " + value;
        },
        "");
}

}  // namespace ltm::common::cli
