#include "runtime/raw_cdr.hpp"

#include <dds/ddsi/ddsi_serdata.h>

#include <map>
#include <mutex>
#include <string>

#include "runtime/dds_error.hpp"

namespace ltm::runtime {

const ddsi_sertype* sertype_of(dds_entity_t participant, const dds_topic_descriptor_t* desc) {
    static std::mutex mutex;
    static std::map<std::pair<dds_entity_t, const dds_topic_descriptor_t*>, const ddsi_sertype*>
        cache;
    std::lock_guard<std::mutex> lock(mutex);
    const auto key = std::make_pair(participant, desc);
    if (auto it = cache.find(key); it != cache.end()) return it->second;

    const std::string name = std::string("ltm_private/sertype_probe/") + desc->m_typename;
    std::string topic_name;
    for (char c : name) topic_name += (c == ':') ? '_' : c;
    const dds_entity_t topic =
        check_dds(dds_create_topic(participant, desc, topic_name.c_str(), nullptr, nullptr),
                  "creating the probe topic of " + std::string(desc->m_typename));
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    // Local only: nothing of the probe leaves the process.
    dds_qset_ignorelocal(qos, DDS_IGNORELOCAL_NONE);
    const dds_entity_t reader = dds_create_reader(participant, topic, qos, nullptr);
    const dds_entity_t writer = dds_create_writer(participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    void* sample = dds_alloc(desc->m_size);  // zeroed: empty strings and sequences
    const ddsi_sertype* type = nullptr;
    if (reader > 0 && writer > 0 && dds_write(writer, sample) == DDS_RETCODE_OK) {
        ddsi_serdata* sd = nullptr;
        dds_sample_info_t info;
        if (dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE) == 1) {
            type = sd->type;  // lives as long as the domain holds topics of this type
            ddsi_serdata_unref(sd);
        }
    }
    dds_free(sample);
    if (writer > 0) dds_delete(writer);
    if (reader > 0) dds_delete(reader);
    // The probe topic stays: it keeps the sertype referenced while the participant lives.
    if (!type)
        throw DdsError(std::string("probing the serialization of ") + desc->m_typename,
                       DDS_RETCODE_ERROR);
    cache[key] = type;
    return type;
}

dds_return_t write_cdr(dds_entity_t writer, const ddsi_sertype* type, const std::uint8_t* cdr,
                       std::size_t size, dds_time_t source_time) {
    ddsrt_iovec_t iov;
    iov.iov_base = const_cast<std::uint8_t*>(cdr);
    iov.iov_len = size;
    ddsi_serdata* sd = ddsi_serdata_from_ser_iov(type, SDK_DATA, 1, &iov, size);
    if (!sd) return DDS_RETCODE_BAD_PARAMETER;
    if (source_time == 0) return dds_writecdr(writer, sd);  // takes over the reference
    // dds_forwardcdr keeps the serdata's timestamp (dds_writecdr sets it to now).
    sd->statusinfo = 0;
    sd->timestamp.v = source_time;
    return dds_forwardcdr(writer, sd);
}

int take_cdr(dds_entity_t reader, std::vector<std::uint8_t>& out, dds_sample_info_t& info) {
    ddsi_serdata* sd = nullptr;
    const int n = dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE);
    if (n <= 0) return n;
    out.clear();
    if (info.valid_data) {
        out.resize(ddsi_serdata_size(sd));
        ddsi_serdata_to_ser(sd, 0, out.size(), out.data());
    }
    ddsi_serdata_unref(sd);
    return 1;
}

}  // namespace ltm::runtime
