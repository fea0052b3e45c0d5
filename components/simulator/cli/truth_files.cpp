#include "simulator/cli/truth_files.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace ltm::sim::cli {
namespace {

std::ofstream open_out(const std::string& path) {
    std::ofstream out(path);
    if (!out) throw common::IoError(path, "cannot write");
    return out;
}

void close_out(std::ofstream& out, const std::string& path) {
    out.close();
    if (!out) throw common::IoError(path, "write failed");
}

const char* actor_kind_name(ActorKind k) {
    return k == ActorKind::kCar ? "car" : (k == ActorKind::kVan ? "van" : "pedestrian");
}

}  // namespace

void write_identity_calib(const std::string& path) {
    std::ofstream out = open_out(path);
    const char* eye =
        "1.000000000000e+00 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
        "0.000000000000e+00 1.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
        "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00";
    for (const char* name : {"P0", "P1", "P2", "P3", "Tr"}) out << name << ": " << eye << "\n";
    close_out(out, path);
}

void write_labels(const std::string& path, const std::vector<std::uint32_t>& labels) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw common::IoError(path, "cannot write");
    std::vector<unsigned char> bytes(labels.size() * 4);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        for (int b = 0; b < 4; ++b)
            bytes[4 * i + b] = static_cast<unsigned char>(labels[i] >> (8 * b));
    }
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (std::fclose(f) != 0 || !ok) throw common::IoError(path, "write failed");
}

void write_objects(const std::string& path, const Simulator& sim) {
    std::ofstream out = open_out(path);
    out << "# id kind x y base_z yaw_deg length width height changed ground_z x" << kGroundSamples
        << "  (world frame, metres; ground_z: the terrain's height on the footprint's long axis "
           "from one end to the other, evenly spaced: a fence on a slope is sunk to its lowest "
           "ground, base_z, and stands on higher ground elsewhere)\n";
    char line[256];
    for (const auto& o : sim.objects()) {
        const Eigen::Vector3d s = o.size.minCoeff() > 0 ? o.size : default_object_size(o.kind);
        std::snprintf(line, sizeof line, "%u %s %.3f %.3f %.3f %.2f %.2f %.2f %.2f %d", o.id,
                      object_kind_name(o.kind), o.x, o.y, o.base_z, o.yaw * 180.0 / M_PI, s.x(),
                      s.y(), s.z(), sim.plan().is_changed(o.id) ? 1 : 0);
        out << line;
        for (int k = 0; k < kGroundSamples; ++k) {
            const double along = s.x() * (double(k) / double(kGroundSamples - 1) - 0.5);
            const double z =
                sim.terrain().height(o.x + std::cos(o.yaw) * along, o.y + std::sin(o.yaw) * along);
            std::snprintf(line, sizeof line, " %.3f", z);
            out << line;
        }
        out << "\n";
    }
    close_out(out, path);
}

void write_changes(const std::string& path, const Simulator& sim) {
    std::ofstream out = open_out(path);
    out << "# session id kind what  (relative to session 0)\n";
    for (const auto& c : sim.plan().changes) {
        out << c.session << " " << c.id << " " << object_kind_name(c.kind) << " " << c.what << "\n";
    }
    close_out(out, path);
}

void write_actors(const std::string& path, const Simulator& sim) {
    std::ofstream out = open_out(path);
    out << "# id kind path_length_m  (label class 2, object id = id)\n";
    for (const auto& a : sim.actors()) {
        out << a.id() << " " << actor_kind_name(a.kind()) << " " << Polyline(a.path()).length()
            << "\n";
    }
    close_out(out, path);
}

void write_kidnaps(const std::string& path, const std::vector<std::size_t>& frames,
                   const std::vector<double>& stamps) {
    std::ofstream out = open_out(path);
    out << "# frame stamp  (first scans after the robot was moved without being told)\n";
    for (std::size_t i = 0; i < frames.size(); ++i) out << frames[i] << " " << stamps[i] << "\n";
    close_out(out, path);
}

void copy_scenario(const std::string& from, const std::string& to, const std::string& note) {
    std::ifstream in(from);
    if (!in) throw common::IoError(from, "cannot read");
    std::stringstream text;
    text << in.rdbuf();
    std::ofstream out = open_out(to);
    out << text.str();
    if (!text.str().empty() && text.str().back() != '\n') out << "\n";
    out << "# ltm_sim run: " << note << "\n";
    close_out(out, to);
}

}  // namespace ltm::sim::cli
