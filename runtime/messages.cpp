#include "runtime/messages.hpp"

#include "runtime/link_messages.hpp"

namespace ltm::runtime {
namespace {

template <class T>
MessageTypeInfo info() {
    return {MessageTraits<T>::ros_name, MessageTraits<T>::descriptor()->m_typename,
            MessageTraits<T>::descriptor()};
}

}  // namespace

const std::vector<MessageTypeInfo>& known_message_types() {
    static const std::vector<MessageTypeInfo> types = {
        info<msg::Time>(),
        info<msg::Header>(),
        info<msg::PointCloud2>(),
        info<msg::Imu>(),
        info<msg::Point>(),
        info<msg::Pose>(),
        info<msg::PoseStamped>(),
        info<msg::PoseWithCovarianceStamped>(),
        info<msg::TransformStamped>(),
        info<msg::Twist>(),
        info<msg::Odometry>(),
        info<msg::Path>(),
        info<msg::TFMessage>(),
        info<msg::Keyframe>(),
        info<msg::LocalMap>(),
        info<msg::LoopClosure>(),
        info<msg::PoseGraph>(),
        info<msg::LocalisationStatus>(),
        info<msg::MapChangeSet>(),
        info<msg::Mesh>(),
        info<msg::Status>(),
        info<msg::MapRequest>(),
        info<msg::LinkPacket>(),
        info<msg::LinkAck>(),
        info<msg::LinkDelivered>(),
        info<msg::MapVersion>(),
        info<msg::SiteOffer>(),
        info<msg::SiteRequest>(),
        info<msg::SiteChunk>(),
    };
    return types;
}

const MessageTypeInfo* find_message_type_by_dds_name(const std::string& dds_name) {
    for (const auto& t : known_message_types())
        if (t.dds_name == dds_name) return &t;
    return nullptr;
}

}  // namespace ltm::runtime
