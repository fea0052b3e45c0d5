#include "recorder/tools/manifest.hpp"

#include <cstdio>

namespace ltm::recorder::tools {

std::string json_escape(const std::string& s) {
    std::string out;
    out.reserve(s.size() + 2);
    for (const unsigned char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += static_cast<char>(c);
                }
        }
    }
    return out;
}

std::string hex(const void* data, std::size_t size) {
    static const char* digits = "0123456789abcdef";
    const auto* p = static_cast<const unsigned char*>(data);
    std::string out(size * 2, '0');
    for (std::size_t i = 0; i < size; ++i) {
        out[2 * i] = digits[p[i] >> 4];
        out[2 * i + 1] = digits[p[i] & 15];
    }
    return out;
}

void write_manifest(McapReader& reader, std::ostream& out) {
    out << "{\n  \"schemas\": [";
    bool first = true;
    for (const auto& [id, s] : reader.schemas()) {
        out << (first ? "\n" : ",\n") << "    {\"id\": " << id << ", \"name\": \""
            << json_escape(s.name) << "\", \"encoding\": \"" << json_escape(s.encoding)
            << "\", \"data_hex\": \"" << hex(s.data.data(), s.data.size()) << "\"}";
        first = false;
    }
    out << "\n  ],\n  \"channels\": [";
    first = true;
    for (const auto& [id, c] : reader.channels()) {
        out << (first ? "\n" : ",\n") << "    {\"id\": " << id << ", \"schema_id\": " << c.schema_id
            << ", \"topic\": \"" << json_escape(c.topic) << "\", \"message_encoding\": \""
            << json_escape(c.message_encoding) << "\", \"metadata\": {";
        bool first_kv = true;
        for (const auto& [k, v] : c.metadata) {
            out << (first_kv ? "" : ", ") << "\"" << json_escape(k) << "\": \"" << json_escape(v)
                << "\"";
            first_kv = false;
        }
        out << "}}";
        first = false;
    }
    out << "\n  ],\n  \"messages\": [";
    first = true;
    MessageCursor cursor = reader.messages();
    for (MessageView m; cursor.next(m);) {
        out << (first ? "\n" : ",\n") << "    {\"channel_id\": " << m.channel->id
            << ", \"topic\": \"" << json_escape(m.channel->topic)
            << "\", \"sequence\": " << m.sequence << ", \"log_time\": \"" << m.log_time
            << "\", \"publish_time\": \"" << m.publish_time << "\", \"data_hex\": \""
            << hex(m.data, m.size) << "\"}";
        first = false;
    }
    out << "\n  ]\n}\n";
}

}  // namespace ltm::recorder::tools
