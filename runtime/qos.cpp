#include "runtime/qos.hpp"

namespace ltm::runtime {

QosProfile default_profile(TopicRole role) {
    QosProfile p;
    switch (role) {
        case TopicRole::kSensor:
            p.reliable = false;
            p.depth = 5;
            break;
        case TopicRole::kState:
            p.depth = 50;
            break;
        case TopicRole::kMap:
            p.transient_local = true;
            p.depth = 100;
            break;
        case TopicRole::kStream:
            p.keep_all = true;
            p.depth = 8;
            break;
    }
    return p;
}

QosProfile TopicQos::apply(QosProfile base) const {
    base.reliable = reliable.value_or(base.reliable);
    base.transient_local = transient_local.value_or(base.transient_local);
    base.keep_all = keep_all.value_or(base.keep_all);
    base.depth = depth.value_or(base.depth);
    base.max_blocking_s = max_blocking_s.value_or(base.max_blocking_s);
    return base;
}

const char* role_name(TopicRole role) {
    switch (role) {
        case TopicRole::kSensor:
            return "sensor";
        case TopicRole::kState:
            return "state";
        case TopicRole::kMap:
            return "map";
        case TopicRole::kStream:
            return "stream";
    }
    return "?";
}

bool parse_role(const std::string& text, TopicRole& role) {
    for (TopicRole r :
         {TopicRole::kSensor, TopicRole::kState, TopicRole::kMap, TopicRole::kStream}) {
        if (text == role_name(r)) {
            role = r;
            return true;
        }
    }
    return false;
}

namespace {

void fill_common(const QosProfile& p, dds_qos_t* qos) {
    dds_qset_reliability(qos, p.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                         static_cast<dds_duration_t>(p.max_blocking_s * 1e9));
    dds_qset_durability(
        qos, p.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    if (p.keep_all) {
        dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
    } else {
        dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, p.depth);
    }
}

}  // namespace

void fill_writer_qos(const QosProfile& p, dds_qos_t* qos) {
    fill_common(p, qos);
    if (p.transient_local) {
        // Late joiners get the last `depth` samples.
        dds_qset_durability_service(qos, 0, DDS_HISTORY_KEEP_LAST, p.depth, DDS_LENGTH_UNLIMITED,
                                    DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
    }
}

void fill_reader_qos(const QosProfile& p, dds_qos_t* qos) {
    fill_common(p, qos);
    if (p.keep_all) {
        // The bounded input queue: when it is full, the reliable writer blocks (back-pressure).
        dds_qset_resource_limits(qos, p.depth, DDS_LENGTH_UNLIMITED, p.depth);
    }
}

QosProfile matching_reader_profile(const dds_qos_t* writer_qos, int depth) {
    dds_reliability_kind_t reliability = DDS_RELIABILITY_BEST_EFFORT;
    dds_duration_t blocking = 0;
    dds_durability_kind_t durability = DDS_DURABILITY_VOLATILE;
    if (writer_qos) {
        dds_qget_reliability(writer_qos, &reliability, &blocking);
        dds_qget_durability(writer_qos, &durability);
    }
    QosProfile p;
    p.reliable = reliability == DDS_RELIABILITY_RELIABLE;
    p.transient_local = durability != DDS_DURABILITY_VOLATILE;
    p.keep_all = false;
    p.depth = depth;
    return p;
}

}  // namespace ltm::runtime
