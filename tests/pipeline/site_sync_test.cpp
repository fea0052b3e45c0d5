// A base station's new site version reaches the robot's site through the host (issue 26): one
// host process runs both ends (site_publisher on the base station's site, site_receiver on the
// robot's), over loopback DDS with the link's small fragments. The robot holds v0001 and half of
// v0002's chunks from an interrupted transfer; it fetches only the rest of the files it does not
// hold and commits v0002, byte for byte the base station's. And a version on request in the middle
// of a session (`./ltm map commit`: the map_request tool's command commit): committed at once,
// atomic, with the mapping asked to save first when there is one, and the session's end
// commits the next one.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "site/core/incoming_version.hpp"
#include "site/core/sync_test_sites.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

constexpr int kDomain = 64;

class SiteSyncPipeline : public ltm::tests::TempDirTest {
  protected:
    SiteSyncPipeline() : TempDirTest("ltm_site_sync_") {}
};

}  // namespace

TEST_F(SiteSyncPipeline, ANewVersionReachesTheRobotWithOnlyWhatChangedAndResumes) {
    const std::string base = site_sync::test::base_site(dir_);
    const std::string robot = site_sync::test::robot_site(dir_, base);
    // An earlier, interrupted transfer: half of the chunks to send are on the robot's disk.
    const site_sync::VersionOffer offer =
        site_sync::scan_version(base + "/versions/v0002", 2, 4096);
    const std::uint64_t id = site_sync::offer_id(site_sync::write_offer(offer));
    std::size_t kept = 0, to_send = 0;
    {
        site_sync::HeldFiles held;
        held.add_site(robot);
        const site_sync::TransferPlan plan = site_sync::plan_transfer(offer, held);
        to_send = plan.chunks.size();
        site_sync::IncomingVersion in(robot + "/incoming/" + site_sync::hex64(id), offer, plan);
        for (std::size_t i = 0; i < plan.chunks.size(); i += 2, ++kept) {
            const std::string b =
                site_sync::read_chunk(base + "/versions/v0002", offer, plan.chunks[i]);
            ASSERT_EQ(in.accept(plan.chunks[i], site_sync::chunk_hash(b.data(), b.size()), b.data(),
                                b.size()),
                      site_sync::ChunkVerdict::kStored);
        }
    }
    const std::string cfg = write(
        "sync.yaml",
        "domain_id: " + std::to_string(kDomain) +
            "\ndds: {interfaces: [lo], multicast: false, peers: [127.0.0.1], max_message_size: "
            "1456 B, fragment_size: 1344 B}\n"
            "topics:\n"
            "  site/offer: {role: map, depth: 1}\n"
            "  site/request: {role: state, keep_all: true, depth: 64}\n"
            "  site/chunk: {role: state, keep_all: true, depth: 64, max_blocking_s: 0.05}\n"
            "components:\n"
            "  - name: site_publisher\n    type: site_publisher\n    params: {site_dir: " +
            base +
            ", chunk_kib: 4}\n"
            "  - name: site_receiver\n    type: site_receiver\n    params: {site_dir: " +
            robot + ", window_chunks: 16, resend_after_s: 30}\n");
    Process host({kHost, cfg}, path("host"));
    ASSERT_TRUE(host.wait_for_log("received v0002 from the base station", 120)) << host.err();
    EXPECT_NE(host.err().find("offering v0002"), std::string::npos) << host.err();
    EXPECT_NE(host.err().find(std::to_string(kept) + " chunks kept from an earlier start"),
              std::string::npos)
        << host.err();
    host.signal(SIGTERM);
    ASSERT_EQ(host.wait(60), 0) << host.err();
    EXPECT_NE(
        host.err().find("site version received (site_receiver): " + robot + "/versions/v0002"),
        std::string::npos)
        << host.err();

    const auto versions = map::SiteStore(robot).versions();
    ASSERT_EQ(versions.size(), 2u);
    EXPECT_TRUE(versions[1].intact) << versions[1].problem;
    EXPECT_EQ(site_sync::write_offer(site_sync::scan_version(versions[1].dir, 2, 4096)),
              site_sync::write_offer(offer));
    EXPECT_FALSE(fs::exists(robot + "/incoming/" + site_sync::hex64(id)));
    // Only the missing half of the chunks crossed: the publisher's count.
    EXPECT_NE(host.err().find("final: " + std::to_string(to_send - kept) + " chunks sent"),
              std::string::npos)
        << host.err();
}

TEST_F(SiteSyncPipeline, AVersionOnRequestMidSessionThenTheSessionsEndCommitsTheNext) {
    const std::string site = path("site");
    map::SiteStore store(site);
    site_sync::test::session(store, map::test::tiny_map(2), 1);  // v0001
    const std::string dds = "dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}\n";
    const std::string cfg = write("commit.yaml", "domain_id: " + std::to_string(kDomain) +
                                                     "\nnamespace: /sync_commit\n" + dds +
                                                     "components:\n  - name: site\n    type: "
                                                     "site\n    params: {site_dir: " +
                                                     site + "}\n");
    Process host({kHost, cfg}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from v0001", 120)) << host.err();
    // What the session's mapping has saved so far.
    map::SaveOptions options;
    options.link_from = store.start_version("")->map_dir();
    map::save_map(store.staging_map_dir(), map::test::tiny_map(3), options);
    const std::vector<std::string> ask{
        kHost,
        std::string(LTM_SOURCE_DIR) + "/launch_configs/tools/map_request.yaml",
        "--set",
        "map_request.command=commit",
        "--set",
        "domain_id=" + std::to_string(kDomain),
        "--set",
        "namespace=/sync_commit",
        "--set",
        "dds={interfaces: [lo], multicast: false, peers: "
        "[127.0.0.1]}"};
    Process request(ask, path("request"));
    ASSERT_EQ(request.wait(90), 0) << request.err() << host.err();
    EXPECT_NE(request.err().find("committed v0002 (" + site + "/versions/v0002)"),
              std::string::npos)
        << request.err();
    auto versions = store.versions();
    ASSERT_EQ(versions.size(), 2u);
    EXPECT_TRUE(versions[1].intact) << versions[1].problem;
    EXPECT_EQ(map::load_map(versions[1].map_dir()).map.local_maps.size(), 3u);
    EXPECT_TRUE(fs::exists(store.staging_map_dir() + "/manifest.txt"));  // the session goes on
    // The session saves on; its end commits v0003 with the rest.
    map::save_map(store.staging_map_dir(), map::test::tiny_map(4), options);
    map::test::write_maintained_map(store.staging_maintained_map_file(), 3);
    host.signal(SIGTERM);
    ASSERT_EQ(host.wait(60), 0) << host.err();
    versions = store.versions();
    ASSERT_EQ(versions.size(), 3u);
    EXPECT_TRUE(versions[2].intact) << versions[2].problem;
    EXPECT_EQ(map::load_map(versions[2].map_dir()).map.local_maps.size(), 4u);
    EXPECT_EQ(map::load_map(versions[1].map_dir()).map.local_maps.size(), 3u);  // unchanged
}

TEST_F(SiteSyncPipeline, AVersionOnRequestAsksTheMappingToSaveFirst) {
    const std::string site = path("site");
    map::SiteStore store(site);
    site_sync::test::session(store, map::test::tiny_map(2), 1);  // v0001
    const std::string cfg =
        write("mapping.yaml",
              "domain_id: " + std::to_string(kDomain) +
                  "\nnamespace: /sync_save\ndds: {interfaces: [lo], multicast: false, "
                  "peers: [127.0.0.1]}\ncomponents:\n  - name: mapping\n    type: "
                  "mapping\n    params: {site_dir: " +
                  site +
                  ", save_period_s: 0, scan_context: {rings: 6, sectors: 12, max_range: 80, "
                  "min_range: 0, sensor_height: 2}}\n  - name: site\n    type: site\n    "
                  "params: {site_dir: " +
                  site + "}\n");
    Process host({kHost, cfg}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from v0001", 120)) << host.err();
    Process request({kHost, std::string(LTM_SOURCE_DIR) + "/launch_configs/tools/map_request.yaml",
                     "--set", "map_request.command=commit", "--set",
                     "domain_id=" + std::to_string(kDomain), "--set", "namespace=/sync_save",
                     "--set", "dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}"},
                    path("request"));
    ASSERT_EQ(request.wait(90), 0) << request.err() << host.err();
    EXPECT_NE(host.err().find("the mapping saves first"), std::string::npos) << host.err();
    EXPECT_NE(request.err().find("committed v0002"), std::string::npos) << request.err();
    const auto versions = store.versions();
    ASSERT_EQ(versions.size(), 2u);
    EXPECT_TRUE(versions[1].intact) << versions[1].problem;
    EXPECT_EQ(map::load_map(versions[1].map_dir()).map.local_maps.size(), 2u);
    host.signal(SIGTERM);
    EXPECT_EQ(host.wait(60), 0) << host.err();
}
