// The robot's end of a site's versions coming from the base station (issue 26): takes the base
// station's offer (`site/offer`), compares the offered files' hashes with the files of its own
// site's intact versions (site/core/held_files.hpp) and asks (`site/request`) only for the chunks
// of files it does not hold, at most `window_chunks` in flight. Chunks (`site/chunk`) are checked
// (length and hash) and kept on the robot's disk (SITE/incoming/<offer>/), so an interrupted
// transfer goes on after a restart of either side. When every chunk is there the version is
// assembled (held files hard-linked), every file checked against the offer's hash and the version
// checked as a whole, then committed into the robot's site in one rename under the base
// station's number (map::SiteStore::adopt) while the robot holds the site's lock for that moment.
// A damaged transfer is never used. The localisation takes the newest intact version at its next
// start.
// Parameters: site_dir (required), robot (the namespace), keep_versions (10), window_chunks (64),
// resend_after_s (5), request_period_s (0.1).
#include <dds/dds.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "common/core/io_error.hpp"
#include "common/core/one_line.hpp"
#include "map/core/site_lock.hpp"
#include "map/core/site_store.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "site/core/chunk_asker.hpp"
#include "site/core/chunk_codec.hpp"
#include "site/core/held_files.hpp"
#include "site/core/incoming_version.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;
using runtime::PathCheck;
using runtime::TopicRole;

double mono_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::string kib(std::uint64_t bytes) { return std::to_string((bytes + 1023) >> 10) + " KiB"; }

class SiteReceiver : public runtime::Component {
  public:
    explicit SiteReceiver(runtime::ComponentContext& ctx)
        : ctx_(ctx), store_(ctx.params().path("site_dir", "", PathCheck::kNone)) {
        auto& p = ctx.params();
        if (store_.dir().empty()) p.fail("site_dir", "required: the robot's site folder");
        std::string robot = ctx.ns();
        if (!robot.empty() && robot.front() == '/') robot.erase(0, 1);
        robot_ = p.get<std::string>("robot", robot.empty() ? "robot" : robot);
        const int keep = p.get<int>("keep_versions", 10);
        if (keep < 1) p.fail("keep_versions", "must be >= 1");
        keep_ = std::size_t(keep);
        window_ = p.get<std::size_t>("window_chunks", 64);
        if (window_ == 0) p.fail("window_chunks", "must be > 0");
        const double resend = p.get<double>("resend_after_s", 5.0);
        if (!(resend > 0)) p.fail("resend_after_s", "must be > 0");
        const double period = p.get<double>("request_period_s", 0.1);
        if (!(period > 0)) p.fail("request_period_s", "must be > 0");
        asker_ = std::make_unique<ChunkAsker>(window_, resend);
        request_out_ = ctx.advertise<msg::SiteRequest>("site/request", TopicRole::kState);
        ctx.subscribe<msg::SiteOffer>("site/offer", TopicRole::kMap,
                                      [this](const msg::SiteOffer& m) { on_offer(m); });
        ctx.subscribe<msg::SiteChunk>("site/chunk", TopicRole::kState,
                                      [this](const msg::SiteChunk& m) { on_chunk(m); });
        ctx.add_timer(period, [this] { ask(); });
        ctx.add_timer(10.0, [this] { report(); });
    }

    void on_shutdown() override {
        if (incoming_)
            ctx_.log().info(map::version_name(incoming_->offer().number) +
                            " not complete: " + std::to_string(incoming_->missing_count()) +
                            " chunks missing; the ones received stay in " + incoming_->dir());
    }

  private:
    void on_offer(const msg::SiteOffer& m) {
        const std::string text = convert::to_string(m.files);
        if (offer_id(text) != m.offer_id || m.offer_id == current_id_ || m.offer_id == refused_id_)
            return;
        VersionOffer offer;
        try {
            offer = parse_offer(text);
        } catch (const common::IoError& e) {
            ctx_.log().error(std::string("offer refused: ") + e.what());
            refused_id_ = m.offer_id;
            return;
        }
        const std::string name = map::version_name(offer.number);
        std::uint32_t newest = 0;
        for (const map::SiteVersion& v : store_.versions())
            if (v.intact) newest = std::max(newest, v.number);
        if (offer.number <= newest) {
            if (offer.number != reported_current_)
                ctx_.log().info("the base station offers " + name + "; the robot's site has " +
                                map::version_name(newest) + ": nothing to fetch");
            reported_current_ = offer.number;
            return;
        }
        try {
            begin(offer, m.offer_id);
        } catch (const common::IoError& e) {
            ctx_.log().error(name + " not fetched: " + e.what());
            incoming_.reset();
            refused_id_ = m.offer_id;
        }
    }

    void begin(const VersionOffer& offer, std::uint64_t id) {
        const double t0 = mono_s();
        HeldFiles held;
        held.add_site(store_.dir());
        TransferPlan plan = plan_transfer(offer, held);
        // Older transfers (superseded offers) go.
        const fs::path incoming = fs::path(store_.dir()) / "incoming";
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(incoming, ec))
            if (e.path().filename() != hex64(id)) fs::remove_all(e.path(), ec);
        incoming_.reset();
        incoming_ = std::make_unique<IncomingVersion>((incoming / hex64(id)).string(), offer,
                                                      std::move(plan));
        current_id_ = id;
        asker_->reset();
        started_ = mono_s();
        const TransferPlan& p = incoming_->plan();
        ctx_.log().info(
            "the base station offers " + map::version_name(offer.number) + ": " +
            std::to_string(p.files_to_send) + " of " + std::to_string(offer.files.size()) +
            " files to fetch (" + kib(p.bytes_to_send) + " of " + kib(p.bytes_total) + "; " +
            std::to_string(held.size()) + " files held, hashed in " +
            std::to_string(int((started_ - t0) * 1000)) + " ms)" +
            (incoming_->resumed_chunks() ? ", " + std::to_string(incoming_->resumed_chunks()) +
                                               " chunks kept from an earlier start"
                                         : ""));
        if (incoming_->missing_count() == 0) finish();
    }

    void on_chunk(const msg::SiteChunk& m) {
        if (!incoming_ || m.offer_id != current_id_) return;
        const ChunkRef c{m.file, m.chunk};
        if (!incoming_->offer().valid(c)) return;
        wire_ += m.data._length;
        std::string bytes;
        ChunkVerdict v = ChunkVerdict::kDamaged;
        try {
            if (decode_chunk(m.encoding, m.data._buffer, m.data._length,
                             incoming_->offer().chunk_length(c), &bytes))
                v = incoming_->accept(c, m.hash, bytes.data(), bytes.size());
        } catch (const common::IoError& e) {
            ctx_.log().error(std::string("chunk not stored: ") + e.what());
            return;
        }
        if (v == ChunkVerdict::kDamaged) {
            const std::uint64_t n = ++damaged_;
            if (n <= 3 || (n & (n - 1)) == 0)
                ctx_.log().warn("damaged chunk refused (file " + std::to_string(c.file) +
                                ", chunk " + std::to_string(c.chunk) + "), " + std::to_string(n) +
                                " so far");
            return;
        }
        if (v == ChunkVerdict::kStored) bytes_ += bytes.size();
        asker_->received(c, mono_s());
        if (incoming_->missing_count() == 0) finish();
    }

    void ask() {
        if (!incoming_) return;
        if (incoming_->missing_count() == 0) {
            finish();  // a commit that waited for the site's lock
            return;
        }
        const std::vector<ChunkRef> due = asker_->due(incoming_->missing(window_ * 4), mono_s());
        if (due.empty()) return;
        std::vector<std::uint64_t> keys;
        for (const ChunkRef& c : due)
            keys.push_back(std::uint64_t(c.file) | (std::uint64_t(c.chunk) << 32));
        msg::SiteRequest m{};
        m.robot = convert::borrow_string(robot_);
        m.offer_id = current_id_;
        convert::borrow_sequence(m.chunks, keys);
        m.missing = incoming_->missing_count();
        m.total = incoming_->plan().chunks.size();
        request_out_.publish(m);
    }

    void finish() {
        const std::string name = map::version_name(incoming_->offer().number);
        const std::string problem = incoming_->assemble();
        if (!problem.empty()) {
            if (incoming_->missing_count() > 0) {
                ctx_.log().warn(name + " not whole (" + problem + "): asked for again");
                return;
            }
            ctx_.log().error(name + " offered by the base station is not whole (" + problem +
                             "): not used");
            drop(true);
            return;
        }
        std::unique_ptr<map::SiteLock> lock;
        try {
            lock = std::make_unique<map::SiteLock>(store_.lock_file());
        } catch (const common::IoError& e) {
            if (!waiting_for_lock_)
                ctx_.log().info(name + " received; its commit waits for the site: " + e.what());
            waiting_for_lock_ = true;
            return;
        }
        waiting_for_lock_ = false;
        try {
            const map::SiteVersion made =
                store_.adopt(incoming_->version_dir(), incoming_->offer().number, keep_);
            const TransferPlan& p = incoming_->plan();
            const std::string detail =
                name + " from the base station: " + std::to_string(p.files_to_send) + " of " +
                std::to_string(incoming_->offer().files.size()) + " files fetched (" +
                kib(p.bytes_to_send) + " of " + kib(p.bytes_total) + "), " + kib(bytes_) +
                " received as " + kib(wire_) + " on the wire in " +
                std::to_string(mono_s() - started_).substr(0, 5) +
                " s; the localisation uses it at its next start";
            ctx_.log().info("received " + detail + " (" + made.dir + ")");
            for (const std::string& pruned : store_.pruned())
                ctx_.log().info("removed " + pruned + " (more than keep_versions " +
                                std::to_string(keep_) + ")");
            ctx_.report_output("site version received", made.dir, true, detail);
        } catch (const common::IoError& e) {
            ctx_.log().error(name + " received but not committed: " + common::one_line(e.what()));
        }
        drop(true);
    }

    void drop(bool refuse) {
        const std::string dir = incoming_->dir();
        if (refuse) refused_id_ = current_id_;
        incoming_.reset();
        current_id_ = 0;
        bytes_ = wire_ = 0;
        std::error_code ec;
        fs::remove_all(dir, ec);
    }

    void report() {
        if (!incoming_) return;
        ctx_.log().info(map::version_name(incoming_->offer().number) + ": " +
                        std::to_string(incoming_->missing_count()) + " of " +
                        std::to_string(incoming_->plan().chunks.size()) + " chunks missing, " +
                        kib(bytes_) + " received, " + std::to_string(asker_->asked_again()) +
                        " chunks asked again");
    }

    runtime::ComponentContext& ctx_;
    map::SiteStore store_;
    std::string robot_;
    std::size_t keep_ = 10, window_ = 64;
    std::unique_ptr<ChunkAsker> asker_;
    runtime::Publisher<msg::SiteRequest> request_out_;
    std::unique_ptr<IncomingVersion> incoming_;
    std::uint64_t current_id_ = 0, refused_id_ = 0, bytes_ = 0, wire_ = 0, damaged_ = 0;
    std::uint32_t reported_current_ = 0;
    double started_ = 0;
    bool waiting_for_lock_ = false;
};

}  // namespace
}  // namespace ltm::site_sync

LTM_REGISTER_COMPONENT(ltm::site_sync::SiteReceiver, "site_receiver",
                       "robot: fetches the base station's newer site versions (only files it does "
                       "not hold, resumable, checked) and commits them into its site")
