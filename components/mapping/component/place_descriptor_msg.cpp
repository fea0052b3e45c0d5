#include "mapping/component/place_descriptor_msg.hpp"

#include "runtime/convert/dds_string.hpp"

namespace ltm::mapping {

MadeDescriptor from_msg(const msg::PlaceDescriptor& m, std::string* problem) {
    auto fail = [&](const std::string& why) {
        if (problem) *problem = why;
        return MadeDescriptor{};
    };
    if (problem) problem->clear();
    if (m.rings == 0) return {};
    if (m.kind > std::uint8_t(places::ScanContextKind::kMeanVariance))
        return fail("unknown descriptor kind " + std::to_string(int(m.kind)));
    MadeDescriptor d;
    places::ScanContextConfig& c = d.made_with;
    c.kind = places::ScanContextKind(m.kind);
    c.rings = m.rings;
    c.sectors = m.sectors;
    c.max_range = m.max_range;
    c.min_range = m.min_range;
    c.sensor_height = m.sensor_height;
    const std::size_t bins = std::size_t(m.rings) * m.sectors;
    const bool spread = c.kind == places::ScanContextKind::kMeanVariance;
    const auto values = convert::view(m.values), spreads = convert::view(m.spreads);
    const auto occupied = convert::view(m.occupied);
    if (values.size() != bins || occupied.size() != bins || spreads.size() != (spread ? bins : 0))
        return fail("descriptor arrays do not hold " + std::to_string(m.rings) + " x " +
                    std::to_string(m.sectors) + " bins");
    d.descriptor.kind = c.kind;
    d.descriptor.rings = c.rings;
    d.descriptor.sectors = c.sectors;
    d.descriptor.value = convert::to_vector(m.values);
    d.descriptor.spread = convert::to_vector(m.spreads);
    d.descriptor.occupied = convert::to_vector(m.occupied);
    return d;
}

void borrow_into(const MadeDescriptor& d, msg::PlaceDescriptor* out) {
    *out = msg::PlaceDescriptor{};
    if (d.descriptor.empty()) return;
    const places::ScanContextConfig& c = d.made_with;
    out->kind = std::uint8_t(c.kind);
    out->rings = std::uint16_t(c.rings);
    out->sectors = std::uint16_t(c.sectors);
    out->max_range = float(c.max_range);
    out->min_range = float(c.min_range);
    out->sensor_height = float(c.sensor_height);
    convert::borrow_sequence(out->values, d.descriptor.value);
    convert::borrow_sequence(out->spreads, d.descriptor.spread);
    convert::borrow_sequence(out->occupied, d.descriptor.occupied);
}

}  // namespace ltm::mapping
