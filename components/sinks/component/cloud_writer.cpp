// Writes every point cloud it receives (`points`) as DIR/NNNNNN.ply (or KITTI .bin), every finished
// local map (`local_map`) as DIR/local_map_<id>.ply (voxel centres and normals, odometry frame) and
// every mesh chunk (`mesh`) as DIR/mesh_<local map id>.ply (the latest revision of each chunk).
#include <cstdio>
#include <filesystem>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "mesh/component/mesh_messages.hpp"
#include "mesh/core/triangle_mesh.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/pointcloud2.hpp"

namespace ltm::sinks {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class CloudWriter : public runtime::Component {
  public:
    explicit CloudWriter(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        dir_ = p.get<std::string>("dir", "");
        if (dir_.empty()) p.fail("dir", "required parameter is missing (the output folder)");
        std::error_code ec;
        std::filesystem::create_directories(dir_, ec);
        if (ec) p.fail("dir", "cannot create " + dir_ + ": " + ec.message());
        format_ = p.get<std::string>("format", "ply");
        if (format_ != "ply" && format_ != "bin")
            p.fail("format", "expected ply or bin, got '" + format_ + "'");
        every_ = p.get<int>("every", 1);
        if (every_ < 1) p.fail("every", "must be at least 1");
        const auto inputs =
            p.get<std::vector<std::string>>("inputs", {"points", "local_map", "mesh"});
        for (const auto& in : inputs) {
            if (in == "points") {
                ctx.subscribe<msg::PointCloud2>(
                    "points", TopicRole::kSensor,
                    [this](const msg::PointCloud2& m) { on_points(m); });
            } else if (in == "local_map") {
                ctx.subscribe<msg::LocalMap>("local_map", TopicRole::kMap,
                                             [this](const msg::LocalMap& m) { on_local_map(m); });
            } else if (in == "mesh") {
                ctx.subscribe<msg::Mesh>("mesh", TopicRole::kMap,
                                         [this](const msg::Mesh& m) { on_mesh(m); });
            } else {
                p.fail("inputs", "unknown input '" + in + "' (known: points, local_map, mesh)");
            }
        }
    }

    void on_shutdown() override {
        ctx_.log().info("wrote " + std::to_string(written_) + " clouds, " + std::to_string(maps_) +
                        " local maps and " + std::to_string(meshes_) + " mesh chunks to " + dir_ +
                        (rejected_ ? " (" + std::to_string(rejected_) + " rejected)" : ""));
    }

  private:
    void on_points(const msg::PointCloud2& m) {
        const std::size_t index = received_++;
        if (index % every_ != 0) return;
        common::PointCloud cloud;
        const std::string err = convert::from_pointcloud2(m, cloud);
        if (!err.empty()) {
            if (++rejected_ <= 5)
                ctx_.log().warn("rejected point cloud " + std::to_string(index) + ": " + err);
            return;
        }
        char name[32];
        std::snprintf(name, sizeof name, "%06zu.%s", index, format_.c_str());
        const std::string path = dir_ + "/" + name;
        try {
            if (format_ == "bin") {
                common::write_kitti_bin(path, cloud);
            } else {
                common::PlyCloud ply;
                ply.points = std::move(cloud.points);
                ply.intensity = std::move(cloud.intensity);
                common::write_ply(path, ply);
            }
            ++written_;
        } catch (const common::IoError& e) {
            ctx_.log().error(e.what());
        }
    }

    void on_local_map(const msg::LocalMap& m) {
        if (!m.finished) return;  // snapshots of the map being built
        const common::LocalMapData d = convert::from_msg(m);
        const Eigen::Isometry3f T = (d.T_odom_anchor * d.T_anchor_grid).cast<float>();
        common::PlyCloud ply;
        for (const auto& v : d.voxels) {
            ply.points.push_back(T * v.centre);
            ply.normals.push_back(T.linear() * v.normal);
            ply.intensity.push_back(v.stability);
        }
        try {
            common::write_ply(dir_ + "/local_map_" + std::to_string(d.id) + ".ply", ply);
            ++maps_;
        } catch (const common::IoError& e) {
            ctx_.log().error(e.what());
        }
    }

    void on_mesh(const msg::Mesh& m) {
        try {
            // Checked (sizes, indices, finite values), then placed where its anchor is.
            const mesh::PlacedMesh p = mesh::from_msg(m);
            common::write_ply(dir_ + "/mesh_" + std::to_string(m.local_map_id) + ".ply",
                              mesh::transformed(p.mesh, p.T_map_anchor));
            ++meshes_;
        } catch (const std::exception& e) {
            ++rejected_;
            ctx_.log().warn(std::string("rejected mesh chunk: ") + e.what());
        }
    }

    runtime::ComponentContext& ctx_;
    std::string dir_, format_;
    int every_ = 1;
    std::size_t received_ = 0, written_ = 0, maps_ = 0, meshes_ = 0, rejected_ = 0;
};

}  // namespace
}  // namespace ltm::sinks

LTM_REGISTER_COMPONENT(
    ltm::sinks::CloudWriter, "cloud_writer",
    "writes received point clouds (PLY or KITTI .bin) and mesh chunks (PLY) to a folder")
