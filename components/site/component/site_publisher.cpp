// The base station's end of a site's versions on their way to the robots (issue 26): offers the
// site's newest intact version on `site/offer` (transient-local: a robot that starts late gets it
// at once; a newer version committed while it runs is offered within `scan_period_s`) and sends
// the chunks robots ask for on `site/request` as `site/chunk`. It holds no state of a transfer:
// the robot knows what it has (site/core/incoming_version.hpp), so a restarted base station
// simply answers the next requests. A full link (the chunk writer's history) delays the sending,
// never the component.
// Chunks cross compressed when that makes them smaller (site/core/chunk_codec.hpp).
// Parameters: site_dir (required), chunk_kib (16), compression_level (3; 0: none), scan_period_s
// (2), max_queue_chunks (8192).
#include <dds/dds.h>

#include <deque>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "common/core/io_error.hpp"
#include "map/core/site_store.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "site/core/chunk_codec.hpp"
#include "site/core/version_files.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;
using runtime::PathCheck;
using runtime::TopicRole;

class SitePublisher : public runtime::Component {
  public:
    explicit SitePublisher(runtime::ComponentContext& ctx)
        : ctx_(ctx), store_(ctx.params().path("site_dir", "", PathCheck::kNone)) {
        auto& p = ctx.params();
        if (store_.dir().empty()) p.fail("site_dir", "required: the base station's site folder");
        const int kib = p.get<int>("chunk_kib", 16);
        if (kib < 1 || kib > 16384) p.fail("chunk_kib", "must be 1 to 16384");
        chunk_size_ = std::uint32_t(kib) * 1024u;
        level_ = p.get<int>("compression_level", 3);
        if (level_ < 0 || level_ > 19) p.fail("compression_level", "must be 0 (none) to 19");
        const double scan_period = p.get<double>("scan_period_s", 2.0);
        if (!(scan_period > 0)) p.fail("scan_period_s", "must be > 0");
        max_queue_ = p.get<std::size_t>("max_queue_chunks", 8192);
        if (max_queue_ == 0) p.fail("max_queue_chunks", "must be > 0");
        offer_out_ = ctx.advertise<msg::SiteOffer>("site/offer", TopicRole::kMap);
        chunk_out_ = ctx.advertise<msg::SiteChunk>("site/chunk", TopicRole::kState);
        ctx.subscribe<msg::SiteRequest>("site/request", TopicRole::kState,
                                        [this](const msg::SiteRequest& m) { on_request(m); });
        scan();
        ctx.add_timer(scan_period, [this] { scan(); });
        ctx.add_timer(0.01, [this] { send(); });
        ctx.add_timer(10.0, [this] { report(false); });
    }

    void on_shutdown() override { report(true); }

  private:
    // Offers the newest intact version when the versions folder changed.
    void scan() {
        std::error_code ec;
        const auto stamp = fs::last_write_time(store_.dir() + "/versions", ec);
        if (ec || (scanned_ && stamp == versions_stamp_)) return;
        scanned_ = true;
        versions_stamp_ = stamp;
        std::vector<std::string> notes;
        std::optional<map::SiteVersion> newest;
        try {
            newest = store_.start_version("", &notes);
        } catch (const common::IoError& e) {
            ctx_.log().error(e.what());
            return;
        }
        for (const std::string& n : notes) ctx_.log().warn(n);
        if (!newest || newest->number == offer_.number) return;
        try {
            offer_ = scan_version(newest->dir, newest->number, chunk_size_);
        } catch (const common::IoError& e) {
            ctx_.log().error(std::string("cannot offer ") + newest->name + ": " + e.what());
            return;
        }
        version_dir_ = newest->dir;
        text_ = write_offer(offer_);
        id_ = offer_id(text_);
        queue_.clear();
        queued_.clear();
        msg::SiteOffer m{};
        std::string site = store_.dir();
        m.site = convert::borrow_string(site);
        m.version = offer_.number;
        m.offer_id = id_;
        m.files = convert::borrow_string(text_);
        if (!offer_out_.publish(m)) ctx_.log().warn("offer of " + newest->name + " not published");
        ctx_.log().info("offering " + newest->name + " (" + std::to_string(offer_.files.size()) +
                        " files, " + std::to_string(offer_.total_bytes() >> 10) +
                        " KiB) to the robots, offer " + hex64(id_));
    }

    void on_request(const msg::SiteRequest& m) {
        if (m.offer_id != id_) {
            ++stale_requests_;
            return;
        }
        const std::string robot = convert::to_string(m.robot);
        if (robots_.insert(robot).second)
            ctx_.log().info(robot + " asks for " + map::version_name(offer_.number) + ": " +
                            std::to_string(m.missing) + " of " + std::to_string(m.total) +
                            " chunks missing");
        progress_[robot] = {m.missing, m.total};
        for (const std::uint64_t key : convert::view(m.chunks)) {
            const ChunkRef c{std::uint32_t(key), std::uint32_t(key >> 32)};
            if (!offer_.valid(c) || queued_.count(c) || queue_.size() >= max_queue_) continue;
            queue_.push_back(c);
            queued_.insert(c);
        }
    }

    void send() {
        for (int n = 0; n < 64 && !queue_.empty() && !ctx_.stop_requested(); ++n) {
            const ChunkRef c = queue_.front();
            std::string bytes;
            try {
                bytes = read_chunk(version_dir_, offer_, c);
            } catch (const common::IoError& e) {
                ctx_.log().error(std::string("chunk not sent: ") + e.what());
                queued_.erase(c);
                queue_.pop_front();
                continue;
            }
            msg::SiteChunk m{};
            m.offer_id = id_;
            m.file = c.file;
            m.chunk = c.chunk;
            m.hash = chunk_hash(bytes.data(), bytes.size());
            EncodedChunk wire = encode_chunk(bytes, level_);
            m.encoding = std::uint8_t(wire.encoding);
            m.data._buffer = reinterpret_cast<std::uint8_t*>(wire.data.data());
            m.data._length = m.data._maximum = std::uint32_t(wire.data.size());
            m.data._release = false;
            const dds_return_t rc = chunk_out_.try_publish(m);
            if (rc == DDS_RETCODE_TIMEOUT) return;  // the link is full: later
            if (rc != DDS_RETCODE_OK)
                ctx_.log().warn(std::string("chunk not sent (") + dds_strretcode(rc) + ")");
            else
                bytes_sent_ += bytes.size(), wire_bytes_ += wire.data.size(), ++chunks_sent_;
            queued_.erase(c);
            queue_.pop_front();
        }
    }

    void report(bool final) {
        if (chunks_sent_ == 0 && !final) return;
        std::string line = std::string(final ? "final: " : "") + std::to_string(chunks_sent_) +
                           " chunks sent (" + std::to_string(bytes_sent_ >> 10) + " KiB, " +
                           std::to_string(wire_bytes_ >> 10) + " KiB on the wire) of " +
                           map::version_name(offer_.number);
        for (const auto& [robot, p] : progress_)
            line += "; " + robot + " missed " + std::to_string(p.first) + " of " +
                    std::to_string(p.second) + " at its last request";
        if (stale_requests_) line += "; " + std::to_string(stale_requests_) + " stale requests";
        ctx_.log().info(line);
    }

    runtime::ComponentContext& ctx_;
    map::SiteStore store_;
    std::uint32_t chunk_size_ = 16384;
    std::size_t max_queue_ = 8192;
    runtime::Publisher<msg::SiteOffer> offer_out_;
    runtime::Publisher<msg::SiteChunk> chunk_out_;
    bool scanned_ = false;
    fs::file_time_type versions_stamp_{};
    VersionOffer offer_;
    std::string version_dir_, text_;
    std::uint64_t id_ = 0;
    std::deque<ChunkRef> queue_;
    std::set<ChunkRef> queued_;
    std::set<std::string> robots_;
    std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> progress_;
    int level_ = 3;
    std::uint64_t bytes_sent_ = 0, wire_bytes_ = 0, chunks_sent_ = 0, stale_requests_ = 0;
};

}  // namespace
}  // namespace ltm::site_sync

LTM_REGISTER_COMPONENT(ltm::site_sync::SitePublisher, "site_publisher",
                       "base station: offers the site's newest intact version to the robots and "
                       "sends the chunks they ask for (only files they do not hold)")
