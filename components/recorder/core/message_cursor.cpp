#include "recorder/core/message_cursor.hpp"

#include <algorithm>
#include <cstring>

#include "recorder/core/mcap_reader.hpp"

namespace ltm::recorder {

struct MessageCursor::Loaded {
    struct Entry {
        std::uint64_t log_time;
        std::size_t offset;  // of the Message record in bytes
    };
    std::vector<std::uint8_t> bytes;  // uncompressed records
    std::vector<Entry> entries;       // wanted messages, by (log_time, offset)
    std::size_t next = 0;
    std::size_t rank = 0;
};

namespace {
bool later(const std::uint64_t t1, std::size_t r1, std::size_t o1, std::uint64_t t2, std::size_t r2,
           std::size_t o2) {
    if (t1 != t2) return t1 > t2;
    if (r1 != r2) return r1 > r2;
    return o1 > o2;
}
}  // namespace

MessageCursor::MessageCursor(McapReader& reader, const ReadOptions& options)
    : reader_(&reader),
      start_time_(options.start_time),
      end_time_(options.end_time),
      check_crcs_(options.check_crcs) {
    if (!options.topics.empty()) {
        all_channels_ = false;
        topics_.insert(options.topics.begin(), options.topics.end());
        for (const auto& [id, ch] : reader.channels()) {
            if (topics_.count(ch.topic)) wanted_.insert(id);
        }
    }
    const auto& chunks = reader.chunks();
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        if (chunks[i].end_time >= start_time_ && chunks[i].start_time <= end_time_) {
            order_.push_back(i);
        }
    }
    std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) {
        return chunks[a].start_time < chunks[b].start_time;
    });
}

MessageCursor::~MessageCursor() = default;
MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;

void MessageCursor::push_head(std::size_t slot) {
    const Loaded& l = *slots_[slot];
    const auto& e = l.entries[l.next];
    heap_.push_back(Head{e.log_time, l.rank, e.offset, slot});
    std::push_heap(heap_.begin(), heap_.end(), [](const Head& a, const Head& b) {
        return later(a.log_time, a.rank, a.offset, b.log_time, b.rank, b.offset);
    });
}

void MessageCursor::load(std::size_t rank) {
    const ChunkInfo& ci = reader_->chunks()[order_[rank]];
    const std::string at = "at byte " + std::to_string(ci.offset);
    std::vector<std::uint8_t> raw;
    if (ci.length < kRecordPrefix || !reader_->file().read(ci.offset, ci.length, raw)) {
        reader_->report("chunk " + at + " (" + std::to_string(ci.length) +
                        " bytes) lies beyond the end of the file; skipped");
        return;
    }
    auto l = std::make_unique<Loaded>();
    l->rank = rank;
    if (ci.loose_messages) {
        l->bytes = std::move(raw);
    } else {
        std::uint64_t len = 0;
        std::memcpy(&len, raw.data() + 1, 8);
        if (raw[0] != static_cast<std::uint8_t>(Op::kChunk) || len != ci.length - kRecordPrefix) {
            reader_->report("chunk index points " + at + " but finds " + describe_op(raw[0]) +
                            " of " + std::to_string(len) + " bytes there; skipped");
            return;
        }
        ChunkRecord rec;
        try {
            decode_chunk(raw.data() + kRecordPrefix, raw.size() - kRecordPrefix, check_crcs_, rec,
                         l->bytes);
        } catch (const common::FormatError& e) {
            reader_->report("Chunk " + at + ": " + describe(e) + "; skipped");
            return;
        }
    }
    ++chunks_loaded_;
    // Malformed records inside are skipped (the scan and verify report them).
    std::size_t early = 0;
    try {
        for_each_record(
            l->bytes.data(), l->bytes.size(),
            [&](std::uint8_t op, const std::uint8_t* c, std::size_t n, std::size_t off) {
                try {
                    if (op == static_cast<std::uint8_t>(Op::kSchema)) {
                        Schema s;
                        parse_schema(c, n, s);
                        if (s.id != 0) reader_->learn(s);
                    } else if (op == static_cast<std::uint8_t>(Op::kChannel)) {
                        Channel ch;
                        parse_channel(c, n, ch);
                        reader_->learn(ch);
                        if (!all_channels_ && topics_.count(ch.topic)) wanted_.insert(ch.id);
                    } else if (op == static_cast<std::uint8_t>(Op::kMessage)) {
                        MessageRecord m;
                        parse_message(c, n, m);
                        if (m.log_time < start_time_ || m.log_time > end_time_) return;
                        if (!all_channels_ && !wanted_.count(m.channel_id)) return;
                        // Earlier than its chunk says: merging by the chunks' start times could
                        // no longer keep log-time order.
                        if (m.log_time < ci.start_time) {
                            ++early;
                            return;
                        }
                        l->entries.push_back(Loaded::Entry{m.log_time, off});
                    }
                } catch (const common::FormatError&) {
                }
            });
    } catch (const common::FormatError& e) {
        reader_->report("Chunk " + at + ": " + describe(e) + "; read up to there");
    }
    if (early > 0)
        reader_->report("Chunk " + at + ": " + std::to_string(early) +
                        " messages logged before the chunk's start time " +
                        std::to_string(ci.start_time) + "; skipped");
    if (l->entries.empty()) return;
    std::sort(l->entries.begin(), l->entries.end(), [](const auto& a, const auto& b) {
        return a.log_time != b.log_time ? a.log_time < b.log_time : a.offset < b.offset;
    });
    std::size_t slot = 0;
    while (slot < slots_.size() && slots_[slot]) ++slot;
    if (slot == slots_.size()) slots_.emplace_back();
    slots_[slot] = std::move(l);
    push_head(slot);
}

bool MessageCursor::next(MessageView& out) {
    if (retire_ < slots_.size()) slots_[retire_].reset();
    retire_ = static_cast<std::size_t>(-1);
    const auto& chunks = reader_->chunks();
    const auto cmp = [](const Head& a, const Head& b) {
        return later(a.log_time, a.rank, a.offset, b.log_time, b.rank, b.offset);
    };
    while (true) {
        while (
            next_chunk_ < order_.size() &&
            (heap_.empty() || chunks[order_[next_chunk_]].start_time <= heap_.front().log_time)) {
            load(next_chunk_++);
        }
        if (heap_.empty()) return false;
        std::pop_heap(heap_.begin(), heap_.end(), cmp);
        const Head h = heap_.back();
        heap_.pop_back();
        Loaded& l = *slots_[h.slot];
        ++l.next;
        if (l.next < l.entries.size())
            push_head(h.slot);
        else
            retire_ = h.slot;

        std::uint64_t len = 0;
        std::memcpy(&len, l.bytes.data() + h.offset + 1, 8);
        MessageRecord m;
        parse_message(l.bytes.data() + h.offset + kRecordPrefix, static_cast<std::size_t>(len), m);
        const auto ch = reader_->channels().find(m.channel_id);
        if (ch == reader_->channels().end()) {
            reader_->report("Message on unknown channel " + std::to_string(m.channel_id) +
                            " in chunk at byte " + std::to_string(chunks[order_[l.rank]].offset) +
                            "; skipped");
            if (retire_ == h.slot) {
                slots_[h.slot].reset();
                retire_ = static_cast<std::size_t>(-1);
            }
            continue;
        }
        out.channel = &ch->second;
        const auto sc = reader_->schemas().find(ch->second.schema_id);
        out.schema = sc == reader_->schemas().end() ? nullptr : &sc->second;
        out.sequence = m.sequence;
        out.log_time = m.log_time;
        out.publish_time = m.publish_time;
        out.data = m.data;
        out.size = m.size;
        return true;
    }
}

}  // namespace ltm::recorder
