// Raw CDR out of one topic and back into another gives the identical sample.
#include "runtime/raw_cdr.hpp"

#include <gtest/gtest.h>

#include "runtime/messages.hpp"

using namespace ltm::runtime;

TEST(RawCdr, TakeAndRewriteIsLossless) {
    const char* xml =
        "<CycloneDDS><Domain Id=\"any\"><General><Interfaces><NetworkInterface "
        "name=\"lo\"/></Interfaces>"
        "<AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>";
    const dds_entity_t domain = dds_create_domain(213, xml);
    const dds_entity_t pp = dds_create_participant(213, nullptr, nullptr);
    ASSERT_GT(pp, 0);
    const auto* desc = MessageTraits<ltm::msg::Odometry>::descriptor();
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    const dds_entity_t t1 = dds_create_topic(pp, desc, "rt/ltm_test/raw_in", nullptr, nullptr);
    const dds_entity_t t2 = dds_create_topic(pp, desc, "rt/ltm_test/raw_out", nullptr, nullptr);
    const dds_entity_t w1 = dds_create_writer(pp, t1, qos, nullptr),
                       r1 = dds_create_reader(pp, t1, qos, nullptr);
    const dds_entity_t w2 = dds_create_writer(pp, t2, qos, nullptr),
                       r2 = dds_create_reader(pp, t2, qos, nullptr);
    dds_delete_qos(qos);

    char frame[] = "odom", child[] = "lidar";
    ltm::msg::Odometry o{};
    o.header.frame_id = frame;
    o.child_frame_id = child;
    o.header.stamp.sec = 12;
    o.pose.pose.position.x = 3.25;
    o.pose.covariance[35] = 0.5;
    ASSERT_EQ(dds_write(w1, &o), DDS_RETCODE_OK);

    std::vector<std::uint8_t> cdr;
    dds_sample_info_t info;
    ASSERT_EQ(take_cdr(r1, cdr, info), 1);
    ASSERT_TRUE(info.valid_data);
    ASSERT_GT(cdr.size(), 4u);
    EXPECT_EQ(cdr[1], 0x01);                // CDR little endian
    EXPECT_EQ(take_cdr(r1, cdr, info), 0);  // nothing left
    ASSERT_EQ(dds_write(w1, &o), DDS_RETCODE_OK);
    ASSERT_EQ(take_cdr(r1, cdr, info), 1);

    const ddsi_sertype* type = sertype_of(pp, desc);
    ASSERT_NE(type, nullptr);
    EXPECT_EQ(sertype_of(pp, desc), type);  // cached
    ASSERT_EQ(write_cdr(w2, type, cdr.data(), cdr.size()), DDS_RETCODE_OK);
    void* buf[1] = {nullptr};
    ASSERT_EQ(dds_take(r2, buf, &info, 1, 1), 1);
    const auto* back = static_cast<const ltm::msg::Odometry*>(buf[0]);
    EXPECT_EQ(std::string(back->child_frame_id), "lidar");
    EXPECT_EQ(back->pose.pose.position.x, 3.25);
    EXPECT_EQ(back->pose.covariance[35], 0.5);
    EXPECT_EQ(back->header.stamp.sec, 12);
    dds_return_loan(r2, buf, 1);
    dds_delete(pp);
    dds_delete(domain);
}
