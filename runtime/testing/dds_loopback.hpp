#pragma once
// For tests: a message written through Cyclone DDS and taken back (serialised, delivered and
// deserialised in one process, on a domain bound to the loopback interface without multicast).
//   runtime::testing::DdsLoopback dds(226);  // a domain id no other test of the binary uses
//   dds.roundtrip(msg, [&](const msg::Mesh& back) { EXPECT_...; });
//   std::vector<std::uint8_t> cdr = dds.serialize(msg);  // the bytes Cyclone puts on the wire
#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "runtime/messages.hpp"

namespace ltm::runtime::testing {

class DdsLoopback {
  public:
    explicit DdsLoopback(dds_domainid_t id) {
        const char* xml =
            "<CycloneDDS><Domain Id=\"any\"><General><Interfaces><NetworkInterface "
            "name=\"lo\"/></Interfaces>"
            "<AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>";
        domain_ = dds_create_domain(id, xml);
        participant_ = dds_create_participant(id, nullptr, nullptr);
    }
    ~DdsLoopback() {
        if (participant_ > 0) dds_delete(participant_);
        if (domain_ > 0) dds_delete(domain_);
    }
    DdsLoopback(const DdsLoopback&) = delete;
    DdsLoopback& operator=(const DdsLoopback&) = delete;

    // Writes `in` on a new topic of T (reliable) and hands the sample taken back to `check`
    // (local delivery is synchronous: the sample is there when dds_write returns).
    template <class T>
    void roundtrip(const T& in, const std::function<void(const T&)>& check) {
        dds_entity_t reader = 0, writer = 0;
        ASSERT_NO_FATAL_FAILURE(open<T>(&reader, &writer));
        ASSERT_EQ(dds_write(writer, &in), DDS_RETCODE_OK);
        void* buf[1] = {nullptr};
        dds_sample_info_t info;
        ASSERT_EQ(dds_take(reader, buf, &info, 1, 1), 1);
        ASSERT_TRUE(info.valid_data);
        check(*static_cast<const T*>(buf[0]));
        dds_return_loan(reader, buf, 1);
        dds_delete(writer);
        dds_delete(reader);
    }

    // The serialized CDR of `in` (with its encapsulation header), as Cyclone puts it on the
    // wire: written and taken back as CDR. Empty (and a test failure) when DDS refuses.
    template <class T>
    std::vector<std::uint8_t> serialize(const T& in) {
        std::vector<std::uint8_t> out;
        dds_entity_t reader = 0, writer = 0;
        open<T>(&reader, &writer);
        if (reader <= 0 || writer <= 0) return out;
        EXPECT_EQ(dds_write(writer, &in), DDS_RETCODE_OK);
        struct ddsi_serdata* sd = nullptr;
        dds_sample_info_t info;
        if (dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE) == 1) {
            out.resize(ddsi_serdata_size(sd));
            ddsi_serdata_to_ser(sd, 0, out.size(), out.data());
            ddsi_serdata_unref(sd);
        }
        EXPECT_FALSE(out.empty()) << "no sample taken back";
        dds_delete(writer);
        dds_delete(reader);
        return out;
    }

  private:
    // A reliable reader and writer of a new topic of T.
    template <class T>
    void open(dds_entity_t* reader, dds_entity_t* writer) {
        ASSERT_GT(participant_, 0) << dds_strretcode(participant_);
        const std::string name = "rt/ltm_test/roundtrip_" + std::to_string(topics_++);
        const dds_entity_t topic = dds_create_topic(participant_, MessageTraits<T>::descriptor(),
                                                    name.c_str(), nullptr, nullptr);
        ASSERT_GT(topic, 0) << dds_strretcode(topic);
        dds_qos_t* qos = dds_create_qos();
        dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
        *reader = dds_create_reader(participant_, topic, qos, nullptr);
        *writer = dds_create_writer(participant_, topic, qos, nullptr);
        dds_delete_qos(qos);
        ASSERT_GT(*reader, 0) << dds_strretcode(*reader);
        ASSERT_GT(*writer, 0) << dds_strretcode(*writer);
    }

    dds_entity_t domain_ = 0, participant_ = 0;
    int topics_ = 0;
};

}  // namespace ltm::runtime::testing
