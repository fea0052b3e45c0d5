// A version reaches the robot's site over a simulated lossy link: chunks and requests dropped at
// random (fixed seed), only what changed sent (bytes counted), a restart of the robot mid-way
// keeps what is on its disk, a damaged chunk is refused, a damaged file is asked for again, and
// the version committed into the robot's site is byte for byte the base station's.
#include "site/core/incoming_version.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <random>

#include "common/core/file_io.hpp"
#include "map/core/site_check.hpp"
#include "site/core/chunk_asker.hpp"
#include "site/core/sync_test_sites.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(LTM_BINARY_DIR) / "site_sync_test" / "incoming";
constexpr std::uint32_t kChunk = 4096;

// The base station and a lossy link, simulated: requests and chunks lost with probability `loss`.
struct LossyLink {
    std::string version_dir;
    const VersionOffer* offer = nullptr;
    double loss = 0;
    std::mt19937 rng{7};
    std::uint64_t bytes_sent = 0, chunks_sent = 0;

    // The chunks that arrive of those asked.
    std::vector<std::pair<ChunkRef, std::string>> ask(const std::vector<ChunkRef>& asked) {
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<std::pair<ChunkRef, std::string>> out;
        for (const ChunkRef& c : asked) {
            if (u(rng) < loss) continue;  // the request lost
            std::string bytes = read_chunk(version_dir, *offer, c);
            bytes_sent += bytes.size();
            ++chunks_sent;
            if (u(rng) < loss) continue;  // the chunk lost
            out.emplace_back(c, std::move(bytes));
        }
        return out;
    }
};

// Changes one byte of a file.
void flip(const std::string& path, std::streamoff at) {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekg(at);
    const char c = char(f.get());
    f.seekp(at);
    f.put(char(c ^ 0x5a));
}

// Runs the transfer until complete or `max_steps` steps of 0.1 s (simulated); true when complete.
bool run(IncomingVersion& in, ChunkAsker& asker, LossyLink& link, double& now,
         std::size_t max_steps = 100000) {
    for (std::size_t step = 0; step < max_steps && in.missing_count() > 0; ++step) {
        now += 0.1;
        for (auto& [c, bytes] : link.ask(asker.due(in.missing(256), now))) {
            EXPECT_NE(
                in.accept(c, chunk_hash(bytes.data(), bytes.size()), bytes.data(), bytes.size()),
                ChunkVerdict::kDamaged);
            asker.received(c, now);
        }
    }
    return in.missing_count() == 0;
}

struct Sites {
    std::string base, robot, incoming;
    VersionOffer offer;
    TransferPlan plan;
    explicit Sites(const std::string& name) {
        base = test::base_site(kRoot / name);
        robot = test::robot_site(kRoot / name, base);
        incoming = robot + "/incoming/" + name;
        offer = scan_version(base + "/versions/v0002", 2, kChunk);
        HeldFiles held;
        held.add_site(robot);
        plan = plan_transfer(offer, held);
    }
    // Every file of the robot's v0002 is the base station's, byte for byte.
    void expect_same_version() const {
        const auto versions = map::SiteStore(robot).versions();
        ASSERT_EQ(versions.size(), 2u);
        EXPECT_TRUE(versions[1].intact) << versions[1].problem;
        const VersionOffer got = scan_version(versions[1].dir, 2, kChunk);
        EXPECT_EQ(write_offer(got), write_offer(offer));
    }
};

TEST(IncomingVersion, AVersionCrossesALossyLinkWithOnlyWhatChanged) {
    Sites s("lossy");
    IncomingVersion in(s.incoming, s.offer, s.plan);
    ChunkAsker asker(16, 2.0);
    LossyLink link{s.base + "/versions/v0002", &s.offer, 0.3};
    double now = 0;
    ASSERT_TRUE(run(in, asker, link, now));
    EXPECT_GT(asker.asked_again(), 0u);  // losses were repaired by asking again
    // Every byte the plan sends crossed at least once; nothing else did.
    EXPECT_EQ(in.bytes_stored(), s.plan.bytes_to_send);
    EXPECT_GE(link.bytes_sent, s.plan.bytes_to_send);
    EXPECT_LT(s.plan.bytes_to_send * 2, s.plan.bytes_total);
    ASSERT_EQ(in.assemble(), "");
    map::SiteStore store(s.robot);
    const map::SiteVersion made = store.adopt(in.version_dir(), s.offer.number, 10);
    EXPECT_EQ(made.name, "v0002");
    s.expect_same_version();
    // Unchanged files are the robot's own (hard links), not copies.
    std::size_t linked = 0;
    for (const auto& e : fs::recursive_directory_iterator(made.dir + "/map/local_maps"))
        linked += fs::hard_link_count(e.path()) > 1 ? 1 : 0;
    EXPECT_GE(linked, 3u);
}

TEST(IncomingVersion, ARestartMidTransferKeepsTheChunksOnDisk) {
    Sites s("restart");
    std::size_t before = 0;
    {
        IncomingVersion in(s.incoming, s.offer, s.plan);
        ChunkAsker asker(8, 2.0);
        LossyLink link{s.base + "/versions/v0002", &s.offer, 0.2};
        double now = 0;
        EXPECT_FALSE(run(in, asker, link, now, 20));  // cut short: the robot restarts
        before = s.plan.chunks.size() - in.missing_count();
        ASSERT_GT(before, 0u);
    }
    // A torn last record (power loss while appending) is ignored.
    {
        std::ofstream j(s.incoming + "/received", std::ios::binary | std::ios::app);
        j << "torn";
    }
    IncomingVersion in(s.incoming, s.offer, s.plan);
    EXPECT_EQ(in.resumed_chunks(), before);
    EXPECT_EQ(in.missing_count(), s.plan.chunks.size() - before);
    std::uint64_t rest = 0;  // the bytes still to come
    for (const ChunkRef& c : in.missing(s.plan.chunks.size())) rest += s.offer.chunk_length(c);
    ChunkAsker asker(8, 2.0);  // a restarted base station answers the same (it holds no state)
    LossyLink link{s.base + "/versions/v0002", &s.offer, 0.2};
    double now = 0;
    ASSERT_TRUE(run(in, asker, link, now));
    EXPECT_EQ(in.bytes_stored(), rest);  // what was on the disk did not cross again
    EXPECT_LT(link.chunks_sent, s.plan.chunks.size() * 2);
    ASSERT_EQ(in.assemble(), "");
    map::SiteStore(s.robot).adopt(in.version_dir(), 2, 10);
    s.expect_same_version();
}

TEST(IncomingVersion, DamagedChunksAreRefusedAndDamagedFilesAskedAgain) {
    Sites s("damage");
    const std::string vdir = s.base + "/versions/v0002";
    {
        IncomingVersion in(s.incoming, s.offer, s.plan);
        const ChunkRef c = s.plan.chunks.front();
        std::string bytes = read_chunk(vdir, s.offer, c);
        const std::uint64_t hash = chunk_hash(bytes.data(), bytes.size());
        std::string flipped = bytes;
        flipped[flipped.size() / 2] ^= 0x10;
        EXPECT_EQ(in.accept(c, hash, flipped.data(), flipped.size()), ChunkVerdict::kDamaged);
        EXPECT_EQ(in.accept(c, hash, bytes.data(), bytes.size() - 1), ChunkVerdict::kDamaged);
        EXPECT_FALSE(in.has(c));
        EXPECT_EQ(in.accept(c, hash, bytes.data(), bytes.size()), ChunkVerdict::kStored);
        EXPECT_EQ(in.accept(c, hash, bytes.data(), bytes.size()), ChunkVerdict::kDuplicate);
        EXPECT_EQ(in.accept({9999, 0}, hash, bytes.data(), bytes.size()), ChunkVerdict::kNotAsked);
    }
    // A stored chunk damaged on the robot's disk while it was off is not kept on the resume.
    flip(s.incoming + "/parts/f" + std::to_string(s.plan.chunks.front().file), 10);
    IncomingVersion in(s.incoming, s.offer, s.plan);
    EXPECT_EQ(in.resumed_chunks(), 0u);
    ChunkAsker asker(16, 2.0);
    LossyLink link{vdir, &s.offer, 0.0};
    double now = 0;
    ASSERT_TRUE(run(in, asker, link, now));
    // A file damaged after every chunk arrived (the disk): the version is not made, the file is
    // asked for again.
    const std::uint32_t f = s.plan.chunks.back().file;
    flip(s.incoming + "/parts/f" + std::to_string(f), 0);
    const std::string problem = in.assemble();
    EXPECT_NE(problem.find(s.offer.files[f].path + ": received bytes do not have the offer's"),
              std::string::npos)
        << problem;
    EXPECT_FALSE(fs::exists(in.version_dir()));
    EXPECT_EQ(in.missing_count(), std::size_t(s.offer.chunks(f)));
    // A file the robot held, damaged on its disk since: asked for too.
    std::string held_path;
    std::uint32_t held_file = 0;
    for (std::uint32_t i = 0; i < s.plan.local_source.size(); ++i)
        if (!s.plan.sends(i) && s.offer.files[i].path.rfind("map/local_maps/", 0) == 0) {
            held_path = s.plan.local_source[i];
            held_file = i;
        }
    ASSERT_FALSE(held_path.empty());
    fs::resize_file(held_path, fs::file_size(held_path) - 3);
    ASSERT_TRUE(run(in, asker, link, now));
    EXPECT_NE(in.assemble().find(s.offer.files[held_file].path + ": held bytes"),
              std::string::npos);
    EXPECT_EQ(in.missing_count(), std::size_t(s.offer.chunks(held_file)));
    ASSERT_TRUE(run(in, asker, link, now));
    ASSERT_EQ(in.assemble(), "");
    map::SiteStore(s.robot).adopt(in.version_dir(), 2, 10);
    s.expect_same_version();
    EXPECT_NE(map::check_map_dir(s.robot + "/versions/v0001/map"), "");  // its own damage stays
}

TEST(SiteStoreAdopt, RefusesAFolderThatIsNotWholeOrANumberTaken) {
    Sites s("adopt");
    map::SiteStore store(s.robot);
    const fs::path half = kRoot / "adopt" / "half";
    fs::remove_all(half);
    fs::copy(s.base + "/versions/v0002", half, fs::copy_options::recursive);
    fs::remove(half / "map/manifest.txt");
    EXPECT_THROW(store.adopt(half.string(), 2, 10), common::IoError);
    EXPECT_EQ(store.versions().size(), 1u);
    fs::remove_all(half);
    fs::copy(s.base + "/versions/v0002", half, fs::copy_options::recursive);
    try {
        store.adopt(half.string(), 1, 10);
        ADD_FAILURE() << "v0001 taken twice";
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("has a v0001 already"), std::string::npos);
    }
    EXPECT_EQ(store.adopt(half.string(), 2, 1).name, "v0002");
    EXPECT_EQ(store.pruned(), std::vector<std::string>{"v0001"});
}

}  // namespace
}  // namespace ltm::site_sync
