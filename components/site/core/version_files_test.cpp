// An offer lists every file of a version with its hash; its text round-trips; text that is not a
// whole offer, or names paths outside the version, is refused in one line; the plan sends only
// the files the robot does not hold (oracle: the files of v0002 not byte-equal to one of v0001).
#include "site/core/version_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_manifest.hpp"
#include "site/core/sync_test_sites.hpp"
#include "site/core/transfer_plan.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(LTM_BINARY_DIR) / "site_sync_test" / "files";

TEST(VersionFiles, AnOfferListsEveryFileAndRoundTrips) {
    const std::string base = test::base_site(kRoot / "offer");  // its own: ctest runs tests at once
    const VersionOffer offer = scan_version(base + "/versions/v0002", 2, 4096);
    ASSERT_GE(offer.files.size(), 8u);
    bool manifest = false, maintained = false, summary = false;
    for (const VersionFile& f : offer.files) {
        manifest |= f.path == "map/manifest.txt";
        maintained |= f.path == "maintenance/long_term_map.bin";
        summary |= f.path == "version.txt";
        EXPECT_EQ(f.hash, map::map_file_hash(
                              common::read_file(base + "/versions/v0002/" + f.path, f.path)));
    }
    EXPECT_TRUE(manifest && maintained && summary);
    const std::string text = write_offer(offer);
    const VersionOffer back = parse_offer(text);
    EXPECT_EQ(write_offer(back), text);
    EXPECT_EQ(offer_id(write_offer(back)), offer_id(text));
    // Chunks cover each file exactly.
    for (std::uint32_t f = 0; f < offer.files.size(); ++f) {
        std::uint64_t sum = 0;
        for (std::uint32_t c = 0; c < offer.chunks(f); ++c) sum += offer.chunk_length({f, c});
        EXPECT_EQ(sum, offer.files[f].size);
    }
}

TEST(VersionFiles, BadOffersAreRefusedInOneLine) {
    const std::string good =
        "ltm_site_offer 1\nversion 3\nchunk_size 100\nfile 5 0123456789abcdef map/a.bin\nend 1\n";
    EXPECT_NO_THROW(parse_offer(good));
    const auto refused = [](const std::string& text, const std::string& what) {
        try {
            parse_offer(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const common::FormatError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(what), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    };
    std::string bad = good;
    refused(bad.replace(bad.find("map/a.bin"), 9, "../a.bin"), "line 4: path '../a.bin'");
    bad = good;
    refused(bad.replace(bad.find("map/a.bin"), 9, "/etc/pwd"), "line 4: path '/etc/pwd'");
    bad = good;
    refused(bad.replace(bad.find("map/a.bin"), 9, "map//a.bi"), "not a plain relative path");
    refused(good.substr(0, good.find("end")), "cut short");
    bad = good;
    refused(bad.replace(bad.find("end 1"), 5, "end 2"), "end line");
    bad = good;
    refused(bad.replace(bad.find("0123"), 4, "xyz0"), "line 4: expected 'file");
    refused("something else\n", "line 1: not a site offer");
    refused(good + "file 1 0123456789abcdef z\n", "after the end");
}

TEST(TransferPlan, OnlyFilesTheRobotDoesNotHoldAreSent) {
    const std::string base = test::base_site(kRoot / "plan");
    const std::string robot = test::robot_site(kRoot / "plan", base);
    const VersionOffer offer = scan_version(base + "/versions/v0002", 2, 4096);
    HeldFiles held;
    held.add_site(robot);
    const TransferPlan plan = plan_transfer(offer, held);

    // Oracle: a file is sent when no file of the robot's v0001 has the same bytes.
    std::vector<std::string> robot_files;
    for (const auto& e : fs::recursive_directory_iterator(robot + "/versions/v0001"))
        if (e.is_regular_file()) robot_files.push_back(common::read_file(e.path().string(), ""));
    std::uint64_t expected = 0, total = 0;
    std::size_t expected_files = 0;
    for (std::size_t i = 0; i < offer.files.size(); ++i) {
        const std::string bytes =
            common::read_file(base + "/versions/v0002/" + offer.files[i].path, "");
        total += bytes.size();
        const bool held_here =
            std::find(robot_files.begin(), robot_files.end(), bytes) != robot_files.end();
        EXPECT_EQ(plan.sends(i), !held_here) << offer.files[i].path;
        if (!held_here) {
            expected += bytes.size();
            ++expected_files;
        }
    }
    EXPECT_EQ(plan.bytes_to_send, expected);
    EXPECT_EQ(plan.files_to_send, expected_files);
    EXPECT_EQ(plan.bytes_total, total);
    // Three of five local maps are unchanged: well under the whole version crosses.
    EXPECT_LT(plan.bytes_to_send * 2, plan.bytes_total);
    EXPECT_GT(plan.bytes_to_send, 0u);
}

}  // namespace
}  // namespace ltm::site_sync
