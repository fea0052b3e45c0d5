// The CDR bytes Cyclone DDS puts on the wire for a PointCloud2 equal a layout written by hand from
// the ROS 2 definition (XCDR1, little endian, as rmw_cyclonedds exchanges it).
#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "runtime/messages.hpp"

namespace {

class Bytes {
  public:
    void u8(std::uint8_t v) { b_.push_back(v); }
    void align(std::size_t n) {
        while ((b_.size() - 4) % n)
            b_.push_back(0);  // alignment counts from after the encapsulation
    }
    void u32(std::uint32_t v) {
        align(4);
        for (int i = 0; i < 4; ++i) b_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void str(const std::string& s) {
        u32(static_cast<std::uint32_t>(s.size() + 1));
        for (char c : s) b_.push_back(static_cast<std::uint8_t>(c));
        b_.push_back(0);
    }
    std::vector<std::uint8_t>& data() { return b_; }

  private:
    std::vector<std::uint8_t> b_;
};

// Takes the serialized form of one sample written on `topic` (same participant, so matching is
// immediate and synchronous).
std::vector<std::uint8_t> serialize(dds_entity_t participant, const ltm::msg::PointCloud2& sample) {
    const dds_entity_t topic =
        dds_create_topic(participant, &sensor_msgs_msg_dds__PointCloud2__desc,
                         "rt/ltm_test/cdr_layout", nullptr, nullptr);
    EXPECT_GT(topic, 0);
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    const dds_entity_t reader = dds_create_reader(participant, topic, qos, nullptr);
    const dds_entity_t writer = dds_create_writer(participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    EXPECT_EQ(dds_write(writer, &sample), DDS_RETCODE_OK);
    struct ddsi_serdata* sd = nullptr;
    dds_sample_info_t info;
    std::vector<std::uint8_t> out;
    if (dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE) == 1) {
        out.resize(ddsi_serdata_size(sd));
        ddsi_serdata_to_ser(sd, 0, out.size(), out.data());
        ddsi_serdata_unref(sd);
    }
    dds_delete(writer);
    dds_delete(reader);
    return out;
}

}  // namespace

TEST(CdrLayout, PointCloud2MatchesHandWrittenRos2Layout) {
    // A private domain on loopback only: no traffic leaves this process.
    const dds_domainid_t domain_id = 211;
    const char* xml =
        "<CycloneDDS><Domain Id=\"any\"><General><Interfaces><NetworkInterface "
        "name=\"lo\"/></Interfaces>"
        "<AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>";
    const dds_entity_t domain = dds_create_domain(domain_id, xml);
    ASSERT_GT(domain, 0) << dds_strretcode(domain);
    const dds_entity_t participant = dds_create_participant(domain_id, nullptr, nullptr);
    ASSERT_GT(participant, 0);

    char frame[] = "velodyne";
    char fx[] = "x", fi[] = "intensity";
    ltm::msg::PointField fields[2] = {{fx, 0, 7, 1}, {fi, 12, 7, 1}};
    std::uint8_t payload[5] = {1, 2, 3, 4, 5};
    ltm::msg::PointCloud2 pc{};
    pc.header.stamp.sec = 1700000000;
    pc.header.stamp.nanosec = 123456789u;
    pc.header.frame_id = frame;
    pc.height = 1;
    pc.width = 2;
    pc.fields._buffer = fields;
    pc.fields._length = pc.fields._maximum = 2;
    pc.is_bigendian = false;
    pc.point_step = 16;
    pc.row_step = 32;
    pc.data._buffer = payload;
    pc.data._length = pc.data._maximum = 5;
    pc.is_dense = true;

    Bytes b;
    // Encapsulation: CDR_LE (0x0001); options carry the number of padding bytes at the end.
    b.u8(0x00);
    b.u8(0x01);
    b.u8(0x00);
    b.u8(0x00);
    b.i32(1700000000);  // header.stamp.sec
    b.u32(123456789u);  // header.stamp.nanosec
    b.str("velodyne");  // header.frame_id
    b.u32(1);           // height
    b.u32(2);           // width
    b.u32(2);           // fields: length
    b.str("x");
    b.u32(0);
    b.u8(7);
    b.u32(1);  // name, offset, datatype, count
    b.str("intensity");
    b.u32(12);
    b.u8(7);
    b.u32(1);
    b.u8(0);    // is_bigendian
    b.u32(16);  // point_step
    b.u32(32);  // row_step
    b.u32(5);   // data: length
    for (std::uint8_t v : payload) b.u8(v);
    b.u8(1);  // is_dense
    std::vector<std::uint8_t>& expected = b.data();
    const std::size_t padding = (4 - (expected.size() % 4)) % 4;

    const std::vector<std::uint8_t> actual = serialize(participant, pc);
    ASSERT_GE(actual.size(), expected.size());
    // Cyclone may pad to a multiple of 4 and then says so in the options' low two bits.
    ASSERT_TRUE(actual.size() == expected.size() || actual.size() == expected.size() + padding)
        << actual.size() << " vs " << expected.size();
    if (actual.size() > expected.size()) {
        EXPECT_EQ(actual[3] & 0x3, padding);
        expected[3] = actual[3];
    }
    EXPECT_EQ(std::vector<std::uint8_t>(actual.begin(), actual.begin() + expected.size()),
              expected);
    dds_delete(participant);
    dds_delete(domain);
}
