#include "runtime/convert/dds_string.hpp"

namespace ltm::convert {

char* dup_string(std::string_view s) {
    char* out = dds_string_alloc(s.size());  // size + 1 bytes
    if (!s.empty()) std::memcpy(out, s.data(), s.size());
    out[s.size()] = '\0';
    return out;
}

void set_string(char*& field, std::string_view s) {
    char* copy = dup_string(s);
    dds_free(field);
    field = copy;
}

}  // namespace ltm::convert
