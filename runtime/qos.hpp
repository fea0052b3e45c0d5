#pragma once
// Quality of service by topic role (STYLE.md section 4).
#include <dds/dds.h>

#include <optional>
#include <string>

namespace ltm::runtime {

enum class TopicRole {
    kSensor,  // sensor input: best-effort, shallow keep-last; a slow reader drops old scans
    kState,   // odometry, status: reliable keep-last
    kMap,     // maps, graph: reliable, transient-local (late joiners get the history)
    kStream,  // lossless offline processing: reliable keep-all, bounded reader queue, back-pressure
};

struct QosProfile {
    bool reliable = true;
    bool transient_local = false;
    bool keep_all = false;
    int depth = 10;               // keep-last depth, or the reader's queue bound for keep-all
    double max_blocking_s = 0.1;  // a blocked reliable write returns after this and is retried
};

// A `topics:` entry of the launch config: the role and the profile keys it sets for one topic.
// What it leaves unset comes from the role's profile (its role, else the one the component
// declared).
struct TopicQos {
    std::optional<TopicRole> role;
    std::optional<bool> reliable, transient_local, keep_all;
    std::optional<int> depth;
    std::optional<double> max_blocking_s;

    // `base` with the keys this entry sets.
    QosProfile apply(QosProfile base) const;
};

QosProfile default_profile(TopicRole role);
const char* role_name(TopicRole role);
// "sensor", "state", "map", "stream"; false when unknown.
bool parse_role(const std::string& text, TopicRole& role);

// Owning wrapper of a dds_qos_t.
class Qos {
  public:
    Qos() : q_(dds_create_qos()) {}
    ~Qos() { dds_delete_qos(q_); }
    Qos(const Qos&) = delete;
    Qos& operator=(const Qos&) = delete;
    dds_qos_t* get() const { return q_; }

  private:
    dds_qos_t* q_;
};

void fill_writer_qos(const QosProfile& p, dds_qos_t* qos);
void fill_reader_qos(const QosProfile& p, dds_qos_t* qos);

// A reader's profile matching a discovered writer (DCPSPublication's QoS, null: the defaults,
// best-effort volatile): its reliability and durability; keep-last `depth` otherwise.
QosProfile matching_reader_profile(const dds_qos_t* writer_qos, int depth);

}  // namespace ltm::runtime
