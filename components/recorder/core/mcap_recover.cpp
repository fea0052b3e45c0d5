#include "recorder/core/mcap_recover.hpp"

#include <filesystem>
#include <set>

#include "common/core/io_error.hpp"
#include "recorder/core/mcap_reader.hpp"

namespace ltm::recorder {

RecoverResult recover(const std::string& in, const std::string& out, McapWriterConfig config,
                      bool keep_compression) {
    std::error_code ec;
    if (std::filesystem::equivalent(in, out, ec)) {
        throw common::IoError(out, "recover needs an output file other than its input");
    }
    McapReader reader(in);
    config.profile = reader.header().profile;
    config.library = reader.header().library.empty() ? "ltm" : reader.header().library;
    if (keep_compression) {
        for (const auto& c : reader.chunks()) {
            if (!c.loose_messages) {
                parse_compression(c.compression, config.compression);
                break;
            }
        }
    }
    McapWriter writer(out, config);
    std::set<std::uint16_t> schemas, channels;
    auto add_channel = [&](const Channel& ch) {
        if (ch.schema_id != 0 && schemas.insert(ch.schema_id).second) {
            writer.add_schema_record(reader.schemas().at(ch.schema_id));
        }
        writer.add_channel_record(ch);
        channels.insert(ch.id);
    };
    for (const auto& [id, ch] : reader.channels()) {
        if (ch.schema_id == 0 || reader.schemas().count(ch.schema_id)) add_channel(ch);
    }
    MessageCursor cursor = reader.messages();
    for (MessageView m; cursor.next(m);) {
        if (!channels.count(m.channel->id)) {
            if (m.channel->schema_id != 0 && !m.schema) continue;  // channel without its schema
            add_channel(*m.channel);
        }
        const WriteStatus st =
            writer.write(m.channel->id, m.log_time, m.publish_time, m.data, m.size, m.sequence);
        if (st != WriteStatus::kOk) throw common::IoError(out, writer.error());
    }
    if (writer.close() != WriteStatus::kOk) throw common::IoError(out, writer.error());
    RecoverResult result;
    result.messages = writer.stats().messages;
    result.chunks = writer.stats().chunks;
    result.problems = reader.problems();
    return result;
}

}  // namespace ltm::recorder
