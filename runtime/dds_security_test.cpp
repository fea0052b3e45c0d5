// DDS Security from a launch config: the `dds.security` block, and participants of a site
// (launch_configs/security/make_site_certs.sh) talking while participants without its credentials
// (plain, or certified by another CA) neither read nor write. Every participant runs in a process
// of its own (Cyclone configures security per domain, one domain of an id per process); the test
// process itself never touches DDS, so forking is safe.
#include "runtime/dds_security.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "runtime/config_error.hpp"
#include "runtime/domain.hpp"
#include "runtime/launch_config.hpp"
#include "runtime/messages.hpp"

using namespace ltm::runtime;
namespace fs = std::filesystem;

namespace {

const std::string kScript = LTM_SOURCE_DIR "/launch_configs/security/make_site_certs.sh";

// A fresh folder for this test's files.
std::string temp_dir(const std::string& name) {
    const fs::path d = fs::path(::testing::TempDir()) /
                       ("ltm_security_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

std::string security_yaml(const std::string& site, const std::string& who) {
    return "  security:\n    identity_ca: " + site + "/identity_ca.pem\n    certificate: " + site +
           "/" + who + "/cert.pem\n    private_key: " + site + "/" + who +
           "/key.pem\n    permissions_ca: " + site +
           "/permissions_ca.pem\n    governance: " + site +
           "/governance.p7s\n    permissions: " + site + "/" + who + "/permissions.p7s\n";
}

// Loads a launch config (domain `domain`, loopback unicast) with `security` under `dds:`.
LaunchConfig config(const std::string& dir, int domain, const std::string& security) {
    static int n = 0;
    const std::string path = dir + "/launch_" + std::to_string(n++) + ".yaml";
    std::ofstream(path) << "domain_id: " << domain
                        << "\ndds:\n  interfaces: [lo]\n  multicast: false\n  peers: [127.0.0.1]\n"
                        << security << "components:\n  - type: trajectory_writer\n";
    return load_launch_config(path);
}

std::string error_of(const std::string& dir, const std::string& security) {
    try {
        config(dir, 0, security);
    } catch (const ConfigError& e) {
        const std::string s = e.what();
        return s.substr(s.find(": ") + 2);  // "key: problem"
    }
    return "";
}

bool make_site(const std::string& dir, const std::string& args) {
    return std::system(
               ("bash '" + kScript + "' " + args + " '" + dir + "' robot1 robot2 >/dev/null")
                   .c_str()) == 0;
}

const char* const kRobot1Topic = "rt/robot1/ltm_test/secure";

// What one participant saw, sent from its process through a pipe.
struct Seen {
    int ok = 0;        // 1: the participant and its endpoints were created
    int trusted = 0;   // samples received from the site's writer
    int intruder = 0;  // samples received from a writer without the site's credentials
    int matched = 0;   // most remote readers plus writers matched at any time
};

enum class Role { kReader, kWriter, kIntruder };

// Runs one participant: the reader takes samples until it has 5 from the site's writer and
// `min_s` passed; the writer waits for a reader, writes 5 samples and waits for their acks; the
// intruder writes and reads for `min_s`.
Seen participate(const LaunchConfig& cfg, Role role, double min_s, const std::string& name) {
    Seen seen;
    Domain domain(cfg);
    const dds_entity_t topic = domain.topic(name, MessageTraits<ltm::msg::Header>::descriptor());
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
    dds_qset_ignorelocal(qos, DDS_IGNORELOCAL_PARTICIPANT);  // matches are remote ones only
    const dds_entity_t reader = dds_create_reader(domain.participant(), topic, qos, nullptr);
    const dds_entity_t writer = dds_create_writer(domain.participant(), topic, qos, nullptr);
    dds_delete_qos(qos);
    if (reader < 0 || writer < 0) return seen;
    seen.ok = 1;
    std::string frame = role == Role::kIntruder ? "intruder" : "trusted";
    ltm::msg::Header msg{};
    msg.frame_id = frame.data();
    const auto t0 = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    int written = 0;
    for (;;) {
        dds_publication_matched_status_t pub;
        dds_subscription_matched_status_t sub;
        dds_get_publication_matched_status(writer, &pub);
        dds_get_subscription_matched_status(reader, &sub);
        seen.matched = std::max(seen.matched, static_cast<int>(pub.current_count) +
                                                  static_cast<int>(sub.current_count));
        if (role == Role::kIntruder || (role == Role::kWriter && pub.current_count > 0)) {
            if (role == Role::kIntruder || written < 5) {
                msg.stamp.sec = written++;
                dds_write(writer, &msg);
            }
        }
        void* buf[8] = {};
        dds_sample_info_t info[8];
        const int n = dds_take(reader, buf, info, 8, 8);
        for (int i = 0; i < n; ++i) {
            if (!info[i].valid_data) continue;
            const auto* h = static_cast<const ltm::msg::Header*>(buf[i]);
            ++(std::string(h->frame_id) == "trusted" ? seen.trusted : seen.intruder);
        }
        if (n > 0) dds_return_loan(reader, buf, n);
        if (role == Role::kWriter && written == 5) {
            seen.ok = dds_wait_for_acks(writer, DDS_SECS(5)) == DDS_RETCODE_OK ? 1 : 0;
            return seen;
        }
        const bool done = role == Role::kReader ? seen.trusted >= 5 : role == Role::kIntruder;
        if (done && elapsed() > min_s) return seen;
        if (elapsed() > 15) return seen;  // a broken set-up fails the test, it does not hang it
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

// Forks a process running participate(); wait() returns what it saw.
class Participant {
  public:
    // `topic`: robot1's by default (a robot's permissions cover its own namespace).
    Participant(const LaunchConfig& cfg, Role role, double min_s,
                const std::string& topic = kRobot1Topic) {
        if (pipe(fds_) != 0) return;
        pid_ = fork();
        if (pid_ == 0) {
            Seen seen;
            try {
                seen = participate(cfg, role, min_s, topic);
            } catch (const std::exception& e) {
                fprintf(stderr, "participant: %s\n", e.what());
            }
            const ssize_t w = write(fds_[1], &seen, sizeof seen);
            _exit(w == sizeof seen ? 0 : 1);
        }
        close(fds_[1]);
    }
    Seen wait() {
        Seen seen;
        if (pid_ <= 0) return seen;
        if (read(fds_[0], &seen, sizeof seen) != sizeof seen) seen = Seen{};
        close(fds_[0]);
        int status = 0;
        waitpid(pid_, &status, 0);
        return seen;
    }

  private:
    int fds_[2] = {-1, -1};
    pid_t pid_ = -1;
};

}  // namespace

TEST(DdsSecurity, LaunchConfigBlockIsCheckedFileByFile) {
    if (std::system("openssl version >/dev/null 2>&1") != 0) GTEST_SKIP() << "openssl not found";
    const std::string dir = temp_dir("config");
    ASSERT_TRUE(make_site(dir + "/site", ""));
    const LaunchConfig c = config(dir, 3, security_yaml(dir + "/site", "robot1"));
    EXPECT_TRUE(c.dds.security.enabled());
    EXPECT_EQ(c.dds.security.certificate, dir + "/site/robot1/cert.pem");
    EXPECT_FALSE(config(dir, 3, "").dds.security.enabled());  // plain by default

    // --set dds.security=... on a launch config without a dds: block.
    const std::string bare = dir + "/bare.yaml";
    std::ofstream(bare) << "components:\n  - type: trajectory_writer\n";
    std::string flow = "dds.security={";
    for (const char* k : {"identity_ca: identity_ca.pem", "certificate: robot1/cert.pem",
                          "private_key: robot1/key.pem", "permissions_ca: permissions_ca.pem",
                          "governance: governance.p7s", "permissions: robot1/permissions.p7s"})
        flow += std::string(flow.back() == '{' ? "" : ", ") + k;
    const fs::path cwd = fs::current_path();
    fs::current_path(dir + "/site");  // relative paths: from the current folder
    const LaunchConfig set = load_launch_config(bare, {flow + "}"});
    fs::current_path(cwd);
    EXPECT_EQ(set.dds.security.permissions, dir + "/site/robot1/permissions.p7s");

    std::string missing = security_yaml(dir + "/site", "robot1");
    missing.replace(missing.find("robot1/key.pem"), 14, "robot9/key.pem");
    EXPECT_EQ(error_of(dir, missing),
              "dds.security.private_key: no such file: " + dir + "/site/robot9/key.pem");
    std::string unknown = security_yaml(dir + "/site", "robot1") + "    password: x\n";
    EXPECT_NE(error_of(dir, unknown).find("dds.security.password: unknown key"), std::string::npos);
    std::string partial = security_yaml(dir + "/site", "robot1");
    partial.erase(partial.find("    governance:"),
                  partial.find("    permissions:") - partial.find("    governance:"));
    EXPECT_NE(error_of(dir, partial).find("dds.security.governance: missing"), std::string::npos);
    EXPECT_EQ(error_of(dir, "  security: [a]\n"), "dds.security: expected a map");

    // The script is idempotent: a second run keeps every key, certificate and signature.
    const auto stamp = fs::last_write_time(dir + "/site/robot1/permissions.p7s");
    std::ifstream key1(dir + "/site/robot1/key.pem");
    const std::string before((std::istreambuf_iterator<char>(key1)), {});
    ASSERT_TRUE(make_site(dir + "/site", ""));
    std::ifstream key2(dir + "/site/robot1/key.pem");
    EXPECT_EQ(before, std::string((std::istreambuf_iterator<char>(key2)), {}));
    EXPECT_EQ(stamp, fs::last_write_time(dir + "/site/robot1/permissions.p7s"));
    fs::remove_all(dir);
}

TEST(DdsSecurity, OnlyTheSitesParticipantsTalk) {
    std::string searched;
    if (dds_security_plugin_dir(&searched).empty())
        GTEST_SKIP() << "Cyclone DDS Security plugins not found in " << searched;
    if (std::system("openssl version >/dev/null 2>&1") != 0) GTEST_SKIP() << "openssl not found";
    const std::string dir = temp_dir("talk");
    ASSERT_TRUE(make_site(dir + "/site", ""));
    ASSERT_TRUE(make_site(dir + "/other", "--site other"));  // the same names, another CA
    const int domain = 150 + ::getpid() % 60;
    const LaunchConfig base = config(dir, domain, security_yaml(dir + "/site", "base_station"));
    const LaunchConfig robot = config(dir, domain, security_yaml(dir + "/site", "robot1"));
    const LaunchConfig plain = config(dir, domain, "");
    const LaunchConfig foreign = config(dir, domain, security_yaml(dir + "/other", "robot1"));

    Participant intruder_plain(plain, Role::kIntruder, 3.0);
    Participant intruder_foreign(foreign, Role::kIntruder, 3.0);
    Participant reader(base, Role::kReader, 3.0);
    Participant writer(robot, Role::kWriter, 0.0);
    const Seen w = writer.wait(), r = reader.wait();
    const Seen p = intruder_plain.wait(), f = intruder_foreign.wait();

    EXPECT_EQ(w.ok, 1) << "the site's writer: no reader acknowledged its samples";
    EXPECT_EQ(w.matched, 2) << "the robot matched endpoints besides the base station's two";
    EXPECT_EQ(r.ok, 1);
    EXPECT_EQ(r.trusted, 5);
    EXPECT_EQ(r.intruder, 0) << "a participant without the site's credentials reached the site";
    for (const Seen& s : {p, f}) {
        EXPECT_EQ(s.ok, 1);  // it runs, alone
        EXPECT_EQ(s.trusted, 0) << "a participant without the site's credentials read its data";
        EXPECT_EQ(s.matched, 0) << "a participant without the site's credentials matched";
    }
    fs::remove_all(dir);
}

// A robot's permissions cover its own namespace only: robot2, with the site's credentials, may not
// create a reader or a writer on robot1's topic (and so neither reads nor forges robot1's data),
// while robot1 and the base station talk on it.
TEST(DdsSecurity, ARobotCannotReadOrWriteAnotherRobotsTopics) {
    std::string searched;
    if (dds_security_plugin_dir(&searched).empty())
        GTEST_SKIP() << "Cyclone DDS Security plugins not found in " << searched;
    if (std::system("openssl version >/dev/null 2>&1") != 0) GTEST_SKIP() << "openssl not found";
    const std::string dir = temp_dir("namespaces");
    ASSERT_TRUE(make_site(dir + "/site", ""));
    const int domain = 150 + (::getpid() + 30) % 60;
    const LaunchConfig base = config(dir, domain, security_yaml(dir + "/site", "base_station"));
    const LaunchConfig robot1 = config(dir, domain, security_yaml(dir + "/site", "robot1"));
    const LaunchConfig robot2 = config(dir, domain, security_yaml(dir + "/site", "robot2"));

    Participant other(robot2, Role::kIntruder, 3.0);
    Participant reader(base, Role::kReader, 3.0);
    Participant writer(robot1, Role::kWriter, 0.0);
    Participant own(robot2, Role::kIntruder, 1.0, "rt/robot2/ltm_test/secure");
    const Seen w = writer.wait(), r = reader.wait(), o = other.wait(), mine = own.wait();

    EXPECT_EQ(w.ok, 1) << "robot1 could not write its own topic";
    EXPECT_EQ(r.trusted, 5);
    EXPECT_EQ(r.intruder, 0);
    EXPECT_EQ(o.ok, 0) << "robot2 was allowed a reader and a writer on robot1's topic";
    EXPECT_EQ(mine.ok, 1) << "robot2 was refused its own namespace";
    fs::remove_all(dir);
}
