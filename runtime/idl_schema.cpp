#include "runtime/idl_schema.hpp"

#include <set>
#include <sstream>

namespace ltm::runtime {
namespace {

// Appends `file` after its includes; drops #include and include-guard lines.
void inline_file(const std::string& file, std::set<std::string>& done, std::string& out) {
    if (!done.insert(file).second) return;
    const auto it = idl_sources().find(file);
    if (it == idl_sources().end()) return;
    std::istringstream in(it->second);
    std::string line, body;
    while (std::getline(in, line)) {
        if (line.rfind("#include \"", 0) == 0) {
            const std::size_t end = line.find('"', 10);
            inline_file(line.substr(10, end - 10), done, out);
            continue;
        }
        if (line.rfind("#ifndef ", 0) == 0 || line.rfind("#define ", 0) == 0 ||
            line.rfind("#endif", 0) == 0)
            continue;
        body += line + "\n";
    }
    out += "// " + file + "\n" + body;
}

}  // namespace

std::string idl_schema_text(const std::string& ros_name) {
    const std::string file = ros_name + ".idl";
    if (!idl_sources().count(file)) return "";
    std::set<std::string> done;
    std::string out;
    inline_file(file, done, out);
    return out;
}

}  // namespace ltm::runtime
