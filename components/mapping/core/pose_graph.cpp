#include "mapping/core/pose_graph.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

namespace ltm::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// The error of one relative-pose measurement (see the header), whitened.
struct RelativePoseError {
    RelativePoseError(const Eigen::Isometry3d& Z, const Matrix6d& sqrt_information)
        : t_z(Z.translation()),
          q_z_inv(Eigen::Quaterniond(Z.linear()).conjugate()),
          sqrt_information(sqrt_information) {}

    template <typename T>
    bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* residual) const {
        using Vec3 = Eigen::Matrix<T, 3, 1>;
        const Eigen::Map<const Vec3> pa(ta), pb(tb);
        const Eigen::Map<const Eigen::Quaternion<T>> Qa(qa), Qb(qb);
        const Eigen::Quaternion<T> qa_inv = Qa.conjugate();
        const Eigen::Quaternion<T> q_ab = qa_inv * Qb;
        const Vec3 p_ab = qa_inv * (pb - pa);
        const Eigen::Quaternion<T> qz_inv = q_z_inv.cast<T>();
        Eigen::Quaternion<T> dq = qz_inv * q_ab;
        if (dq.w() < T(0)) dq.coeffs() = -dq.coeffs();  // the shorter way round
        Eigen::Matrix<T, 6, 1> e;
        e.template head<3>() = qz_inv * (p_ab - t_z.cast<T>());
        e.template tail<3>() = T(2) * dq.vec();
        Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
        r = sqrt_information.cast<T>() * e;
        return true;
    }

    Eigen::Vector3d t_z;
    Eigen::Quaterniond q_z_inv;
    Matrix6d sqrt_information;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// Upper factor U with U^T U = information (so that |U e|^2 = e^T I e); zero when not positive
// definite.
Matrix6d sqrt_information(const Matrix6d& information) {
    const Eigen::LLT<Matrix6d> llt(0.5 * (information + information.transpose()));
    if (llt.info() != Eigen::Success) return Matrix6d::Zero();
    return llt.matrixU();
}

bool finite_pose(const Eigen::Isometry3d& T) {
    if (!T.matrix().allFinite()) return false;
    const Eigen::Matrix3d R = T.linear();
    return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-5;
}

// Union-find over node indices.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

}  // namespace

std::optional<common::ConfigProblem> validate(const PoseGraphConfig& config) {
    PoseGraphConfig c = config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

PoseGraph::PoseGraph(const PoseGraphConfig& config) : config_(config) {
    common::throw_if(validate(config), "pose_graph");
}

const map::PoseGraphNode* PoseGraph::find(std::uint64_t id) const {
    const auto it = index_.find(id);
    return it == index_.end() ? nullptr : &nodes_[it->second];
}

bool PoseGraph::add_node(const map::PoseGraphNode& node) {
    if (index_.count(node.id) || !finite_pose(node.T_odom_anchor) ||
        !finite_pose(node.T_world_anchor)) {
        return false;
    }
    index_.emplace(node.id, nodes_.size());
    nodes_.push_back(node);
    return true;
}

bool PoseGraph::add_edge(const map::PoseGraphEdge& edge) {
    if (edge.from == edge.to || !index_.count(edge.from) || !index_.count(edge.to) ||
        !finite_pose(edge.T_from_to) || !edge.information.allFinite()) {
        return false;
    }
    edges_.push_back(edge);
    return true;
}

bool PoseGraph::remove_edges(std::uint64_t from, std::uint64_t to, map::EdgeKind kind) {
    const std::size_t before = edges_.size();
    edges_.erase(std::remove_if(edges_.begin(), edges_.end(),
                                [&](const map::PoseGraphEdge& e) {
                                    return e.from == from && e.to == to && e.kind == kind;
                                }),
                 edges_.end());
    return edges_.size() != before;
}

bool PoseGraph::set_pose(std::uint64_t id, const Eigen::Isometry3d& T_world_anchor) {
    const auto it = index_.find(id);
    if (it == index_.end() || !finite_pose(T_world_anchor)) return false;
    nodes_[it->second].T_world_anchor = T_world_anchor;
    return true;
}

bool PoseGraph::set_fixed(std::uint64_t id, bool fixed) {
    const auto it = index_.find(id);
    if (it == index_.end()) return false;
    nodes_[it->second].fixed = fixed;
    return true;
}

void PoseGraph::update_errors() {
    for (map::PoseGraphEdge& e : edges_) {
        const Eigen::Isometry3d& A = nodes_[index_.at(e.from)].T_world_anchor;
        const Eigen::Isometry3d& B = nodes_[index_.at(e.to)].T_world_anchor;
        const Eigen::Isometry3d E = e.T_from_to.inverse() * (A.inverse() * B);
        e.error_translation = E.translation().norm();
        e.error_rotation = Eigen::AngleAxisd(E.linear()).angle();
    }
}

OptimisationSummary PoseGraph::solve_once(const std::vector<char>& hold) {
    OptimisationSummary s;
    const std::size_t n = nodes_.size();
    std::vector<double> t(3 * n), q(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        Eigen::Map<Eigen::Vector3d> ti(&t[3 * i]);
        Eigen::Map<Eigen::Quaterniond> qi(&q[4 * i]);
        ti = nodes_[i].T_world_anchor.translation();
        qi = Eigen::Quaterniond(nodes_[i].T_world_anchor.linear()).normalized();
    }
    // The manifold and the loss (shared by the loop edges) outlive the problem.
    ceres::EigenQuaternionManifold quaternion;
    std::unique_ptr<ceres::LossFunction> loss;
    if (config_.loop_loss == "cauchy") {
        loss = std::make_unique<ceres::CauchyLoss>(config_.loop_loss_scale);
    } else if (config_.loop_loss == "huber") {
        loss = std::make_unique<ceres::HuberLoss>(config_.loop_loss_scale);
    }
    ceres::Problem::Options po;
    po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(po);
    for (const map::PoseGraphEdge& e : edges_) {
        if (!e.active) continue;
        const std::size_t a = index_.at(e.from), b = index_.at(e.to);
        auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 6, 3, 4, 3, 4>(
            new RelativePoseError(e.T_from_to, sqrt_information(e.information)));
        ceres::LossFunction* l = e.kind == map::EdgeKind::kLoop ? loss.get() : nullptr;
        problem.AddResidualBlock(cost, l, &t[3 * a], &q[4 * a], &t[3 * b], &q[4 * b]);
        ++s.edges;
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!problem.HasParameterBlock(&q[4 * i])) continue;  // a node without edges
        problem.SetManifold(&q[4 * i], &quaternion);
        if (hold[i]) {
            problem.SetParameterBlockConstant(&t[3 * i]);
            problem.SetParameterBlockConstant(&q[4 * i]);
        }
    }
    s.nodes = n;
    if (s.edges == 0) {
        s.solved = true;
        s.message = "no edges: nothing to optimise";
        return s;
    }
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    options.max_num_iterations = config_.max_iterations;
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    s.message = summary.BriefReport();
    s.iterations = int(summary.iterations.size());
    s.initial_cost = summary.initial_cost;
    s.final_cost = summary.final_cost;
    s.solved = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
    s.solves = 1;
    if (!s.solved) return s;
    for (std::size_t i = 0; i < n; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() =
            Eigen::Map<const Eigen::Quaterniond>(&q[4 * i]).normalized().toRotationMatrix();
        T.translation() = Eigen::Map<const Eigen::Vector3d>(&t[3 * i]);
        nodes_[i].T_world_anchor = T;
    }
    return s;
}

OptimisationSummary PoseGraph::optimise() {
    // Every loop edge is examined afresh.
    for (map::PoseGraphEdge& e : edges_) {
        if (e.kind == map::EdgeKind::kLoop) e.active = true;
    }
    const std::vector<map::PoseGraphNode> before = nodes_;
    OptimisationSummary total;
    for (int round = 0;; ++round) {
        // Gauge: in every connected part, the fixed nodes, or else its first node, are held.
        std::vector<std::size_t> parent(nodes_.size());
        std::iota(parent.begin(), parent.end(), std::size_t(0));
        for (const map::PoseGraphEdge& e : edges_) {
            if (!e.active) continue;
            parent[root(parent, index_.at(e.from))] = root(parent, index_.at(e.to));
        }
        std::vector<char> hold(nodes_.size(), 0), anchored(nodes_.size(), 0);
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            if (nodes_[i].fixed) hold[i] = anchored[root(parent, i)] = 1;
        }
        total.components = 0;
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            const std::size_t r = root(parent, i);
            if (r == i) ++total.components;
            if (!anchored[r]) hold[i] = anchored[r] = 1;
        }
        const OptimisationSummary s = solve_once(hold);
        if (round == 0) total.initial_cost = s.initial_cost;
        total.final_cost = s.final_cost;
        total.iterations += s.iterations;
        total.solves += s.solves;
        total.nodes = s.nodes;
        total.edges = s.edges;
        total.message = s.message;
        total.solved = s.solved;
        if (!s.solved) {
            nodes_ = before;
            return total;
        }
        update_errors();
        bool rejected = false;
        for (map::PoseGraphEdge& e : edges_) {
            if (e.kind != map::EdgeKind::kLoop || !e.active) continue;
            if (e.error_translation > config_.outlier_translation ||
                e.error_rotation > config_.outlier_rotation * kDegToRad) {
                e.active = false;
                rejected = true;
            }
        }
        if (!rejected || round >= config_.max_outlier_rounds) break;
    }
    for (const map::PoseGraphEdge& e : edges_) {
        if (e.kind != map::EdgeKind::kLoop) continue;
        ++(e.active ? total.loops_active : total.loops_rejected);
    }
    return total;
}

}  // namespace ltm::mapping
