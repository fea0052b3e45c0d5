#pragma once
// The DDS participant of one host process, its Cyclone configuration, and the topics it created.
#include <dds/dds.h>

#include <map>
#include <mutex>
#include <string>

#include "runtime/launch_config.hpp"

namespace ltm::runtime {

class Domain {
  public:
    // Creates the domain (with the launch config's DDS settings) and the participant.
    // Throws DdsError naming what failed.
    explicit Domain(const LaunchConfig& config);
    ~Domain();
    Domain(const Domain&) = delete;
    Domain& operator=(const Domain&) = delete;

    dds_entity_t participant() const { return participant_; }
    int domain_id() const { return domain_id_; }

    // The topic `dds_name` of type `desc`, created once per process. Throws DdsError, or
    // std::invalid_argument when the name is already used with another type.
    dds_entity_t topic(const std::string& dds_name, const dds_topic_descriptor_t* desc);

    // The QoS of a topic: the profile of its role (the launch config's `topics:` role, else the
    // declared one) with the keys its `topics:` entry sets.
    QosProfile profile(const std::string& absolute_name, TopicRole declared) const;
    TopicRole role(const std::string& absolute_name, TopicRole declared) const;

  private:
    // The launch config's `topics:` entry of this topic, null when it has none.
    const TopicQos* topic_qos(const std::string& absolute_name) const;

    const LaunchConfig& config_;
    int domain_id_;
    dds_entity_t domain_ = 0, participant_ = 0;
    std::mutex mutex_;
    std::map<std::string, std::pair<dds_entity_t, const dds_topic_descriptor_t*>> topics_;
};

// The Cyclone DDS XML configuration of the launch config's `dds:` section.
std::string cyclone_xml(const DdsSettings& dds);

}  // namespace ltm::runtime
