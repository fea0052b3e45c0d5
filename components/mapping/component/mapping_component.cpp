// The SLAM back end as a component: `local_map` and `keyframe` in (from the odometry); loop
// closures, the optimised `pose_graph` and the corrected keyframe trajectory (`path`) out. The
// optimisation runs on this component's own thread, off the odometry's. At shutdown the map is
// saved (`map_dir`) and the global voxel map written as PLY (`global_map_file`).
#include <memory>

#include "common/convert/geometry.hpp"
#include "common/convert/local_map.hpp"
#include "common/core/io_error.hpp"
#include "common/core/ply_io.hpp"
#include "mapping/core/map_store.hpp"
#include "mapping/core/mapper.hpp"
#include "runtime/component.hpp"

namespace ltm::mapping {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class MappingComponent : public runtime::Component {
public:
    explicit MappingComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        map_dir_ = p.path("map_dir", "", PathCheck::kParentExists);
        global_map_file_ = p.path("global_map_file", "", PathCheck::kParentExists);
        frame_id_ = p.get<std::string>("frame_id", "map");
        const double save_period = p.get<double>("save_period_s", 30.0);
        if (!map_dir_.empty()) writer_ = std::make_unique<MapWriter>(map_dir_);
        // Saving as it goes keeps the save at shutdown small (only what changed is rewritten),
        // and a crash loses at most one period.
        if (writer_ && save_period > 0) ctx.add_timer(save_period, [this] { save(); });
        MapperConfig config;
        config.max_loops_per_keyframe = p.get<int>("max_loops_per_keyframe", config.max_loops_per_keyframe);
        config.loop_cooldown_keyframes = p.get<int>("loop_cooldown_keyframes", config.loop_cooldown_keyframes);
        config.keep_keyframe_points = p.get<bool>("keep_keyframe_points", config.keep_keyframe_points);
        try {
            mapper_ = std::make_unique<Mapper>(config);
        } catch (const std::exception& e) {
            p.fail("max_loops_per_keyframe", e.what());
        }
        ctx.subscribe<msg::LocalMap>("local_map", TopicRole::kMap, [this](const msg::LocalMap& m) {
            const LocalMapResult r = mapper_->add_local_map(convert::from_msg(m));
            if (!r.added && !r.message.empty()) ctx_.log().debug(r.message);
        });
        ctx.subscribe<msg::Keyframe>("keyframe", TopicRole::kState, [this](const msg::Keyframe& m) { on_keyframe(m); });
        graph_out_ = ctx.advertise<msg::PoseGraph>("pose_graph", TopicRole::kMap);
        path_out_ = ctx.advertise<msg::Path>("path", TopicRole::kMap);
        loop_out_ = ctx.advertise<msg::LoopClosure>("loop_closure", TopicRole::kState);
    }

    void on_shutdown() override {
        if (loops_since_optimise_ > 0) optimise();
        publish_path();
        ctx_.log().info(std::to_string(mapper_->keyframes().size()) + " keyframes, " +
                        std::to_string(mapper_->local_map_count()) + " local maps, " +
                        std::to_string(mapper_->loops().size()) + " loops closed");
        save();
        try {
            if (!global_map_file_.empty()) {
                common::write_ply(global_map_file_, mapper_->global_map());
                ctx_.log().info("global voxel map written to " + global_map_file_);
            }
        } catch (const common::IoError& e) {
            ctx_.log().error(e.what());
        }
    }

private:
    void save() {
        if (!writer_ || mapper_->revision() + mapper_->keyframes().size() + mapper_->local_map_count() == saved_state_)
            return;
        try {
            const SaveStats st = writer_->save(mapper_->snapshot());
            saved_state_ = mapper_->revision() + mapper_->keyframes().size() + mapper_->local_map_count();
            ctx_.log().info("map saved to " + map_dir_ + " (" + std::to_string(st.files_written) + " files written, " +
                            std::to_string(st.bytes_total >> 20) + " MiB in all)");
        } catch (const common::IoError& e) {
            ctx_.log().error(std::string("map not saved: ") + e.what());
        }
    }

    void on_keyframe(const msg::Keyframe& m) {
        const KeyframeResult r = mapper_->add_keyframe(convert::from_msg(m));
        if (!r.added) {
            ctx_.log().warn("keyframe " + std::to_string(m.id) + " not added: " + r.message);
            return;
        }
        for (const LoopClosure& loop : r.loops) publish_loop(loop, m.header.stamp);
        loops_since_optimise_ += r.loops.size();
        if (r.optimisation_due()) optimise();
    }

    void optimise() {
        const OptimisationSummary s = mapper_->optimise();
        loops_since_optimise_ = 0;
        if (!s.solved) {
            ctx_.log().warn("pose graph not solved: " + s.message);
            return;
        }
        publish_graph();
        publish_path();
    }

    void publish_loop(const LoopClosure& loop, const msg::Time& stamp) {
        msg::LoopClosure out{};
        out.header.stamp = stamp;
        out.header.frame_id = const_cast<char*>(frame_id_.c_str());
        const auto& nodes = mapper_->graph().nodes();
        for (const auto& n : nodes) {
            if (n.id == loop.from_node) out.from_map_id = n.local_map_id;
            if (n.id == loop.to_node) out.to_map_id = n.local_map_id;
        }
        out.from_keyframe_id = loop.match_keyframe;
        out.to_keyframe_id = loop.query_keyframe;
        out.relative_pose = convert::to_pose(loop.T_from_to);
        convert::to_array36(loop_information(mapper_->config().loop_edge), out.information);
        out.score = static_cast<float>(loop.descriptor_distance);
        out.fitness = static_cast<float>(loop.inlier_fraction);
        out.residual = static_cast<float>(loop.inlier_rms);
        out.accepted = true;
        loop_out_.publish(out);
        ctx_.log().info("loop closed: scan " + std::to_string(loop.query_scan) + " with scan " +
                        std::to_string(loop.match_scan) + " (" + std::to_string(loop.inliers) + " inliers)");
    }

    void publish_graph() {
        const PoseGraph& g = mapper_->graph();
        std::vector<msg::AnchorPose> anchors;
        std::map<std::uint64_t, std::uint64_t> map_of;
        for (const auto& n : g.nodes()) {
            anchors.push_back({n.local_map_id, convert::to_pose(n.T_world_anchor)});
            map_of[n.id] = n.local_map_id;
        }
        std::vector<msg::PoseGraphEdge> edges;
        for (const auto& e : g.edges()) {
            if (!e.active) continue;
            msg::PoseGraphEdge out{};
            out.from_id = map_of[e.from];
            out.to_id = map_of[e.to];
            out.kind = e.kind == EdgeKind::kOdometry ? ltm_msgs_msg_PoseGraphEdge_Constants_ODOMETRY
                                                     : ltm_msgs_msg_PoseGraphEdge_Constants_LOOP;
            out.relative_pose = convert::to_pose(e.T_from_to);
            convert::to_array36(e.information, out.information);
            edges.push_back(out);
        }
        msg::PoseGraph out{};
        out.header.frame_id = const_cast<char*>(frame_id_.c_str());
        out.revision = static_cast<std::uint32_t>(mapper_->revision());
        out.anchors._buffer = anchors.data();
        out.anchors._length = out.anchors._maximum = static_cast<std::uint32_t>(anchors.size());
        out.edges._buffer = edges.data();
        out.edges._length = out.edges._maximum = static_cast<std::uint32_t>(edges.size());
        graph_out_.publish(out);
    }

    // The corrected trajectory: every keyframe at its optimised pose.
    void publish_path() {
        const auto& keyframes = mapper_->keyframes();
        std::vector<msg::PoseStamped> poses(keyframes.size());
        for (std::uint32_t i = 0; i < keyframes.size(); ++i) {
            poses[i].header.stamp = convert::to_time(keyframes[i]->data.stamp);
            poses[i].header.frame_id = const_cast<char*>(frame_id_.c_str());
            poses[i].pose = convert::to_pose(mapper_->keyframe_pose(i));
        }
        msg::Path path{};
        path.header.frame_id = const_cast<char*>(frame_id_.c_str());
        path.poses._buffer = poses.data();
        path.poses._length = path.poses._maximum = static_cast<std::uint32_t>(poses.size());
        path_out_.publish(path);
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<Mapper> mapper_;
    std::string map_dir_, global_map_file_, frame_id_;
    std::size_t loops_since_optimise_ = 0;
    std::unique_ptr<MapWriter> writer_;
    std::uint64_t saved_state_ = 0;
    runtime::Publisher<msg::PoseGraph> graph_out_;
    runtime::Publisher<msg::Path> path_out_;
    runtime::Publisher<msg::LoopClosure> loop_out_;
};

}  // namespace
}  // namespace ltm::mapping

LTM_REGISTER_COMPONENT(ltm::mapping::MappingComponent, "mapping",
                       "SLAM back end: Scan Context loops, pose graph, corrected path, map saved at shutdown")
