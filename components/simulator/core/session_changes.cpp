#include "simulator/core/session_changes.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::sim {
namespace {

template <typename T>
void shuffle(std::vector<T>& v, Rng& rng) {
    for (std::size_t i = v.size(); i > 1; --i) {
        std::swap(v[i - 1],
                  v[static_cast<std::size_t>(rng.uniform_int(0, static_cast<int>(i) - 1))]);
    }
}

struct SessionEditor {
    const Layout& layout;
    std::vector<ObjectInstance>& objects;
    FreeSpace space;
    const FreeSpace& route_k;
    const FreeSpace& route_0;
    double range;
    int session;
    std::uint32_t& next_id;
    SessionPlan& plan;
    Rng& rng;

    bool visible(const Eigen::Vector2d& p, bool both) const {
        return route_k.corridor_distance(p, range) <= range &&
               (!both || route_0.corridor_distance(p, range) <= range);
    }
    void note(std::uint32_t id, ObjectKind kind, const char* what) {
        plan.changes.push_back({session, id, kind, what});
        plan.changed_ids.push_back(id);
    }
    void remove(std::size_t index, const char* what = "removed") {
        note(objects[index].id, objects[index].kind, what);
        space.remove_footprint(objects[index].id);
        objects.erase(objects.begin() + static_cast<long>(index));
    }
    std::size_t find(std::uint32_t id) const {
        for (std::size_t i = 0; i < objects.size(); ++i) {
            if (objects[i].id == id) return i;
        }
        return objects.size();
    }
    // A free parking slot seen from this session's route, or false.
    bool free_slot(ObjectInstance& v) {
        std::vector<OrientedRect> slots;
        for (const auto& s : layout.parking_slots) {
            if (visible(s.center, false)) slots.push_back(s);
        }
        shuffle(slots, rng);
        for (const auto& s : slots) {
            v.x = s.center.x();
            v.y = s.center.y();
            v.yaw = s.yaw;
            if (space.is_free(v.footprint(), 0.3, 0.3)) return true;
        }
        return false;
    }
    void place(ObjectInstance v, const char* what) {
        settle_on_terrain(v, layout.terrain);
        space.add_footprint(v.footprint(), v.id);
        objects.push_back(v);
        note(v.id, v.kind, what);
    }
};

}  // namespace

bool SessionPlan::is_changed(std::uint32_t id) const {
    return std::binary_search(changed_ids.begin(), changed_ids.end(), id);
}

SessionPlan plan_sessions(const Layout& layout, const std::vector<SessionConfig>& sessions,
                          const std::vector<Points2>& routes, std::uint64_t seed,
                          double visible_range) {
    SessionPlan plan;
    plan.objects.assign(sessions.size(), layout.objects);
    std::uint32_t next_id = layout.next_id;
    FreeSpace route_0(10.0);
    if (!routes.empty()) route_0.add_corridor(routes[0], 0.0);
    for (std::size_t k = 1; k < sessions.size(); ++k) {
        const ChangesConfig& c = sessions[k].changes;
        FreeSpace route_k(10.0);
        route_k.add_corridor(routes[k], 0.0);
        Rng rng(hash_mix(seed, 0xC4A46E, k));
        SessionEditor ed{layout,        plan.objects[k],     layout.free_space, route_k, route_0,
                         visible_range, static_cast<int>(k), next_id,           plan,    rng};
        const std::string where = "sessions[" + std::to_string(k) + "].changes.";
        auto warn_short = [&](const char* key, int asked, int done) {
            if (done < asked) {
                plan.warnings.push_back(where + key + ": " + std::to_string(done) + " of " +
                                        std::to_string(asked) +
                                        " possible (too few candidates near both routes)");
            }
        };
        std::vector<std::uint32_t> parked, fences;
        for (const auto& o : ed.objects) {
            const Eigen::Vector2d p(o.x, o.y);
            if (o.parked && ed.visible(p, true)) parked.push_back(o.id);
            if (o.kind == ObjectKind::kFence && o.size.x() >= 6.0 && ed.visible(p, true))
                fences.push_back(o.id);
        }
        shuffle(parked, rng);
        shuffle(fences, rng);
        int done = 0;
        for (; done < c.remove_parked && !parked.empty(); ++done) {
            ed.remove(ed.find(parked.back()));
            parked.pop_back();
        }
        warn_short("remove_parked", c.remove_parked, done);
        done = 0;
        while (done < c.move_parked && !parked.empty()) {
            const std::size_t i = ed.find(parked.back());
            parked.pop_back();
            ObjectInstance v = ed.objects[i];
            ed.space.remove_footprint(v.id);
            if (!ed.free_slot(v)) {
                ed.space.add_footprint(ed.objects[i].footprint(), v.id);
                continue;
            }
            ed.objects.erase(ed.objects.begin() + static_cast<long>(i));
            ed.place(v, "moved");
            ++done;
        }
        warn_short("move_parked", c.move_parked, done);
        done = 0;
        for (int n = 0; n < c.add_parked; ++n) {
            ObjectInstance v;
            v.kind = rng.chance(0.75) ? ObjectKind::kCar : ObjectKind::kVan;
            v.size = default_object_size(v.kind);
            v.parked = true;
            v.seed = rng.next();
            if (!ed.free_slot(v)) break;
            v.id = next_id++;
            ed.place(v, "added");
            ++done;
        }
        warn_short("add_parked", c.add_parked, done);
        done = 0;
        const Polyline line(routes[k]);
        for (int n = 0, tries = 0; n < c.add_containers && tries < 500; ++tries) {
            const double s = rng.uniform(0, line.length());
            const Eigen::Vector2d p = line.point_at(s), t = line.tangent_at(s);
            const double side = rng.chance(0.5) ? 1.0 : -1.0;
            ObjectInstance box;
            box.kind = ObjectKind::kContainer;
            box.size = default_object_size(box.kind);
            box.seed = rng.next();
            const Eigen::Vector2d q = p + side * Eigen::Vector2d(-t.y(), t.x()) *
                                              (layout.road_half + rng.uniform(2.0, 6.0));
            box.x = q.x();
            box.y = q.y();
            box.yaw = std::atan2(t.y(), t.x());
            if (!layout.terrain.covered(q.x(), q.y()) ||
                !ed.space.is_free(box.footprint(), 0.8, 0.6))
                continue;
            box.id = next_id++;
            ed.place(box, "added");
            ++n;
            ++done;
        }
        warn_short("add_containers", c.add_containers, done);
        done = 0;
        for (; done < c.remove_fence_segments && !fences.empty(); ++done) {
            ed.remove(ed.find(fences.back()));
            fences.pop_back();
        }
        warn_short("remove_fence_segments", c.remove_fence_segments, done);
        for (const auto& a : c.add) {
            ObjectInstance o;
            o.kind = a.kind;
            o.x = a.x;
            o.y = a.y;
            o.yaw = a.yaw_deg * M_PI / 180.0;
            o.size = a.size;
            o.parked = a.parked;
            o.seed = rng.next();
            o.id = next_id++;
            ed.place(o, "added");
        }
        for (const auto& p : c.remove_at) {
            std::size_t best = ed.objects.size();
            double best_d = 3.0;
            for (std::size_t i = 0; i < ed.objects.size(); ++i) {
                const double d =
                    ed.objects[i].footprint().contains(p)
                        ? 0.0
                        : (Eigen::Vector2d(ed.objects[i].x, ed.objects[i].y) - p).norm();
                if (d <= best_d) {
                    best_d = d;
                    best = i;
                }
            }
            if (best < ed.objects.size()) {
                ed.remove(best);
            } else {
                plan.warnings.push_back(where + "remove_at: nothing stands at (" +
                                        std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")");
            }
        }
    }
    std::sort(plan.changed_ids.begin(), plan.changed_ids.end());
    plan.changed_ids.erase(std::unique(plan.changed_ids.begin(), plan.changed_ids.end()),
                           plan.changed_ids.end());
    return plan;
}

}  // namespace ltm::sim
