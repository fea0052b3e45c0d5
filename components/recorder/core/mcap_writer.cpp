#include "recorder/core/mcap_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "common/core/crc32.hpp"
#include "common/core/io_error.hpp"

namespace ltm::recorder {

const char* write_status_name(WriteStatus s) {
    switch (s) {
        case WriteStatus::kOk:
            return "ok";
        case WriteStatus::kDiskFull:
            return "disk full";
        case WriteStatus::kIoError:
            return "I/O error";
        case WriteStatus::kClosed:
            return "writer closed";
        case WriteStatus::kUnknownChannel:
            return "unknown channel";
    }
    return "?";
}

McapWriter::McapWriter(const std::string& path, McapWriterConfig config)
    : path_(path),
      config_(std::move(config)),
      compressor_(config_.compression, config_.compression_level) {
    if (config_.chunk_size == 0) throw std::invalid_argument("chunk_size must be > 0");
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw common::IoError(path, std::string("cannot create: ") + std::strerror(errno));
    std::vector<std::uint8_t> head(kMcapMagic, kMcapMagic + kMagicSize);
    write_header(head, Header{config_.profile, config_.library});
    data_crc_ = common::crc32_init();
    if (!write_bytes(head.data(), head.size())) {
        const int err = errno;
        ::close(fd_);
        fd_ = -1;
        throw common::IoError(path, std::string("cannot write: ") + std::strerror(err));
    }
    chunk_.reserve(config_.chunk_size + (config_.chunk_size >> 2));
}

McapWriter::~McapWriter() { close(); }

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
    const std::uint32_t id = schemas_.empty() ? 1u : schemas_.rbegin()->first + 1u;
    if (id > 0xFFFFu) throw std::invalid_argument("more than 65535 schemas");
    add_schema_record(Schema{static_cast<std::uint16_t>(id), name, encoding, data});
    return static_cast<std::uint16_t>(id);
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
    const std::uint32_t id = channels_.empty() ? 1u : channels_.rbegin()->first + 1u;
    if (id > 0xFFFFu) throw std::invalid_argument("more than 65535 channels");
    add_channel_record(
        Channel{static_cast<std::uint16_t>(id), schema_id, topic, message_encoding, metadata});
    return static_cast<std::uint16_t>(id);
}

void McapWriter::add_schema_record(const Schema& schema) {
    if (schema.id == 0) throw std::invalid_argument("schema id 0 is reserved");
    const auto [it, inserted] = schemas_.emplace(schema.id, schema);
    if (!inserted && !(it->second == schema)) {
        throw std::invalid_argument("schema id " + std::to_string(schema.id) + " already used");
    }
}

void McapWriter::add_channel_record(const Channel& channel) {
    if (channel.schema_id != 0 && !schemas_.count(channel.schema_id)) {
        throw std::invalid_argument("channel '" + channel.topic + "': unknown schema id " +
                                    std::to_string(channel.schema_id));
    }
    const auto [it, inserted] = channels_.emplace(channel.id, channel);
    if (!inserted && !(it->second == channel)) {
        throw std::invalid_argument("channel id " + std::to_string(channel.id) + " already used");
    }
}

void McapWriter::start_chunk_channel(std::uint16_t channel_id) {
    const Channel& ch = channels_.at(channel_id);
    if (ch.schema_id != 0 && chunk_schemas_.insert(ch.schema_id).second) {
        write_schema(chunk_, schemas_.at(ch.schema_id));
    }
    write_channel(chunk_, ch);
    chunk_channels_.insert(channel_id);
}

WriteStatus McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time,
                              std::uint64_t publish_time, const void* data, std::size_t size) {
    return write(channel_id, log_time, publish_time, data, size, ++next_sequence_[channel_id]);
}

WriteStatus McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time,
                              std::uint64_t publish_time, const void* data, std::size_t size,
                              std::uint32_t sequence) {
    if (fd_ < 0) return WriteStatus::kClosed;
    if (!channels_.count(channel_id)) return WriteStatus::kUnknownChannel;
    if (!chunk_channels_.count(channel_id)) start_chunk_channel(channel_id);
    if (chunk_messages_ == 0) {
        chunk_start_time_ = chunk_end_time_ = log_time;
    } else {
        chunk_start_time_ = std::min(chunk_start_time_, log_time);
        chunk_end_time_ = std::max(chunk_end_time_, log_time);
    }
    chunk_index_[channel_id].emplace_back(log_time, chunk_.size());
    write_message(chunk_, MessageRecord{channel_id, sequence, log_time, publish_time,
                                        static_cast<const std::uint8_t*>(data), size});
    ++chunk_messages_;
    chunk_payload_ += size;
    const bool full = chunk_.size() >= config_.chunk_size;
    const bool long_enough = config_.max_chunk_duration != 0 &&
                             chunk_end_time_ - chunk_start_time_ >= config_.max_chunk_duration;
    return full || long_enough ? write_chunk() : WriteStatus::kOk;
}

WriteStatus McapWriter::flush() {
    if (fd_ < 0) return WriteStatus::kClosed;
    return write_chunk();
}

bool McapWriter::write_bytes(const std::uint8_t* p, std::size_t n) {
    data_crc_ = common::crc32_update(data_crc_, p, n);
    while (n > 0) {
        const ssize_t got = ::write(fd_, p, n);
        if (got < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        p += got;
        n -= static_cast<std::size_t>(got);
        pos_ += static_cast<std::uint64_t>(got);
    }
    stats_.file_bytes = pos_;
    return true;
}

WriteStatus McapWriter::write_chunk() {
    if (chunk_.empty()) return WriteStatus::kOk;
    const std::uint64_t good_pos = pos_;
    const std::uint32_t good_crc = data_crc_;

    ChunkRecord rec;
    rec.message_start_time = chunk_start_time_;
    rec.message_end_time = chunk_end_time_;
    rec.uncompressed_size = chunk_.size();
    rec.uncompressed_crc = common::crc32(chunk_.data(), chunk_.size());
    rec.compression = compression_name(config_.compression);
    const std::vector<std::uint8_t>* body = &chunk_;
    if (config_.compression != Compression::kNone) {
        try {
            compressor_.compress(chunk_.data(), chunk_.size(), compressed_);
        } catch (const std::runtime_error& e) {
            return fail(0, std::string("compression failed: ") + e.what(), good_pos, good_crc);
        }
        body = &compressed_;
    }
    rec.records_size = body->size();

    scratch_.clear();
    const std::size_t prefix = write_chunk_prefix(scratch_, rec);
    ChunkIndex ci;
    ci.message_start_time = rec.message_start_time;
    ci.message_end_time = rec.message_end_time;
    ci.chunk_start_offset = pos_;
    ci.chunk_length = prefix + body->size();
    ci.compression = rec.compression;
    ci.compressed_size = body->size();
    ci.uncompressed_size = rec.uncompressed_size;

    // Message indexes follow the chunk: one record a channel, entries in log-time order.
    std::vector<std::uint8_t> indexes;
    for (auto& [channel_id, entries] : chunk_index_) {
        std::stable_sort(entries.begin(), entries.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        ci.message_index_offsets[channel_id] =
            ci.chunk_start_offset + ci.chunk_length + indexes.size();
        write_message_index(indexes, channel_id, entries);
    }
    ci.message_index_length = indexes.size();

    if (!write_bytes(scratch_.data(), scratch_.size()) ||
        !write_bytes(body->data(), body->size()) || !write_bytes(indexes.data(), indexes.size())) {
        return fail(errno, "cannot write chunk at byte " + std::to_string(good_pos), good_pos,
                    good_crc);
    }
    chunk_indexes_.push_back(std::move(ci));
    ++statistics_.chunk_count;
    for (const auto& [channel_id, entries] : chunk_index_) {
        statistics_.channel_message_counts[channel_id] += entries.size();
    }
    if (statistics_.message_count == 0) {
        statistics_.message_start_time = chunk_start_time_;
        statistics_.message_end_time = chunk_end_time_;
    } else {
        statistics_.message_start_time =
            std::min(statistics_.message_start_time, chunk_start_time_);
        statistics_.message_end_time = std::max(statistics_.message_end_time, chunk_end_time_);
    }
    statistics_.message_count += chunk_messages_;
    stats_.messages += chunk_messages_;
    stats_.message_bytes += chunk_payload_;
    stats_.chunks += 1;
    stats_.uncompressed_bytes += chunk_.size();

    chunk_.clear();
    chunk_schemas_.clear();
    chunk_channels_.clear();
    chunk_index_.clear();
    chunk_messages_ = chunk_payload_ = 0;
    if (config_.sync && ::fdatasync(fd_) != 0) {
        return fail(errno, "fdatasync failed after chunk at byte " + std::to_string(good_pos), pos_,
                    data_crc_);
    }
    return WriteStatus::kOk;
}

bool McapWriter::write_tail() {
    std::vector<std::uint8_t> tail;
    write_data_end(tail, common::crc32_final(data_crc_));
    const std::uint64_t summary_start = pos_ + tail.size();
    const std::size_t summary_begin = tail.size();
    std::vector<SummaryOffset> offsets;
    auto group = [&](Op op, std::size_t begin) {
        if (tail.size() > begin) {
            offsets.push_back(
                SummaryOffset{static_cast<std::uint8_t>(op), pos_ + begin, tail.size() - begin});
        }
    };
    std::size_t begin = tail.size();
    for (const auto& [id, s] : schemas_) write_schema(tail, s);
    group(Op::kSchema, begin);
    begin = tail.size();
    for (const auto& [id, c] : channels_) write_channel(tail, c);
    group(Op::kChannel, begin);
    begin = tail.size();
    Statistics st = statistics_;
    st.schema_count = static_cast<std::uint16_t>(schemas_.size());
    st.channel_count = static_cast<std::uint32_t>(channels_.size());
    write_statistics(tail, st);
    group(Op::kStatistics, begin);
    begin = tail.size();
    for (const auto& ci : chunk_indexes_) write_chunk_index(tail, ci);
    group(Op::kChunkIndex, begin);
    const std::uint64_t summary_offset_start = pos_ + tail.size();
    for (const auto& so : offsets) write_summary_offset(tail, so);
    const std::size_t footer_begin = tail.size();
    write_footer(tail, Footer{summary_start, summary_offset_start, 0});
    // The summary CRC covers the summary, the summary offsets and the footer up to summary_crc.
    const std::uint32_t crc = common::crc32(tail.data() + summary_begin,
                                            footer_begin + kRecordPrefix + 16 - summary_begin);
    std::memcpy(tail.data() + footer_begin + kRecordPrefix + 16, &crc, 4);
    tail.insert(tail.end(), kMcapMagic, kMcapMagic + kMagicSize);
    return write_bytes(tail.data(), tail.size());
}

WriteStatus McapWriter::fail(int err, const std::string& what, std::uint64_t good_pos,
                             std::uint32_t good_crc) {
    const bool no_room = err == ENOSPC || err == EFBIG || err == EDQUOT;
    stats_.lost_messages += chunk_messages_;
    error_ = path_ + ": " + (no_room ? "disk full: " : "") + what +
             (err ? std::string(" (") + std::strerror(err) + ")" : std::string()) +
             "; recording stopped, " + std::to_string(stats_.messages) + " messages kept in " +
             std::to_string(stats_.chunks) + " chunks, " + std::to_string(chunk_messages_) +
             " lost";
    // Cut the partial chunk, then try to finish the file (the summary is small and the cut chunk
    // freed its space). If even that fails, cut back again: the file then ends after its last
    // complete chunk, which the reader reads and recover() completes.
    bool closed_cleanly = false;
    if (::ftruncate(fd_, static_cast<off_t>(good_pos)) == 0 &&
        ::lseek(fd_, static_cast<off_t>(good_pos), SEEK_SET) >= 0) {
        pos_ = good_pos;
        data_crc_ = good_crc;
        closed_cleanly = write_tail();
        if (!closed_cleanly && ::ftruncate(fd_, static_cast<off_t>(good_pos)) == 0) pos_ = good_pos;
    }
    if (!closed_cleanly) error_ += "; file left without summary (use recover)";
    stats_.file_bytes = pos_;
    ::close(fd_);
    fd_ = -1;
    failed_ = true;
    chunk_.clear();
    chunk_index_.clear();
    chunk_messages_ = chunk_payload_ = 0;
    return no_room ? WriteStatus::kDiskFull : WriteStatus::kIoError;
}

WriteStatus McapWriter::close() {
    if (fd_ < 0) return failed_ ? WriteStatus::kClosed : WriteStatus::kOk;
    const WriteStatus st = write_chunk();
    if (st != WriteStatus::kOk) return st;  // fail() closed the file
    const std::uint64_t good_pos = pos_;
    const std::uint32_t good_crc = data_crc_;
    if (!write_tail()) return fail(errno, "cannot write summary", good_pos, good_crc);
    if (config_.sync && ::fdatasync(fd_) != 0) {
        return fail(errno, "fdatasync failed at close", pos_, data_crc_);
    }
    if (::close(fd_) != 0) {
        fd_ = -1;
        failed_ = true;
        error_ = path_ + ": close failed: " + std::strerror(errno);
        return WriteStatus::kIoError;
    }
    fd_ = -1;
    return WriteStatus::kOk;
}

}  // namespace ltm::recorder
