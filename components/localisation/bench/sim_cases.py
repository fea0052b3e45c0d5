#!/usr/bin/env python3
"""The scenario of `sim_cases.sh`: two drives of one stretch of KITTI 00's real path through the
simulator's town. Session 0 (the map) keeps every MAP_STEP-th pose; session 1 (the queries) every
QUERY_STEP-th, shifted sideways by 3 m x sin(2 pi i / 300) (0-3 m either side of the map's
path, i the pose index), so a query stands beside and between the map's keyframes.
  sim_cases.py OUT_DIR SENSOR FIRST LAST [MAP_STEP QUERY_STEP [WORLD]]
WORLD: town (kitti00_path's: houses, blocks, street trees, parked cars) or avenue (a road lined
with trees, few buildings; the query drive on another day: parked cars moved, removed, added).
Writes OUT_DIR/scenario.yaml, map_poses.txt, map_times.txt, query_poses.txt, query_times.txt."""
import math
import os
import sys


def main():
    out, sensor, first, last = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    map_step = int(sys.argv[5]) if len(sys.argv) > 5 else 5
    query_step = int(sys.argv[6]) if len(sys.argv) > 6 else 2
    world = sys.argv[7] if len(sys.argv) > 7 else "town"
    if world not in ("town", "avenue"):
        sys.exit("sim_cases.py: unknown world '%s' (town, avenue)" % world)
    data = os.environ.get("LTM_SHARED_DATA")
    kitti = os.path.join(data, "kitti")
    poses = [list(map(float, l.split())) for l in open(os.path.join(kitti, "poses/00.txt"))]
    times = [float(l) for l in open(os.path.join(kitti, "times/00.txt"))]
    last = min(last, len(poses))
    os.makedirs(out, exist_ok=True)

    def write(name, indices, lateral):
        with open(os.path.join(out, name + "_poses.txt"), "w") as fp, \
                open(os.path.join(out, name + "_times.txt"), "w") as ft:
            for i in indices:
                p = poses[i][:]
                d = lateral(i)
                # camera frame: x right; the pose moved d along its own x axis
                for r in range(3):
                    p[4 * r + 3] += p[4 * r + 0] * d
                fp.write(" ".join("%.9e" % v for v in p) + "\n")
                ft.write("%.6f\n" % times[i])

    write("map", range(first, last, map_step), lambda i: 0.0)
    write("query", range(first, last, query_step),
          lambda i: 3.0 * math.sin(2.0 * math.pi * i / 300.0))
    calib = os.path.join(kitti, "sequences/00/calib.txt")
    route = "    route: {{poses_file: {0}_poses.txt, times_file: {0}_times.txt, " \
            "calib_file: " + calib + ", camera_frame: true}}\n"
    with open(os.path.join(out, "scenario.yaml"), "w") as f:
        f.write("# written by components/localisation/bench/sim_cases.py\n")
        f.write("name: kitti00_two_drives\nseed: 2012\n")
        f.write("sensor: {model: %s, height: 1.73, ego_box: [-2.1, -0.8, -2.0, 1.9, 0.8, -0.7]}\n"
                % sensor)
        town = ("{parked_car_probability: 0.4, tree_spacing: 8, pole_spacing: 35, "
                "building_probability: 0.85, second_row_probability: 0.6}")
        trees = 1.0
        if world == "avenue":
            town = ("{parked_car_probability: 0.3, tree_spacing: 6, pole_spacing: 50, "
                    "building_probability: 0.15, second_row_probability: 0.1}")
            trees = 3.0
        f.write("world:\n  style: town\n  margin: 60\n  road_width: 3.2\n  tree_density: %.1f\n"
                "  terrain: {amplitude: 1.5, wavelength: 200, cell: 2}\n  town: %s\n"
                % (trees, town))
        f.write("sessions:\n")
        f.write("  - name: map\n    start_time: 0\n" + route.format("map") +
                "    actors: {vehicles: 8, pedestrians: 12}\n")
        f.write("  - name: queries\n    start_time: %d\n" % (86400 if world == "avenue" else 0) + route.format("query") +
                "    actors: {vehicles: 8, pedestrians: 12}\n")
        if world == "avenue":
            f.write("    changes: {move_parked: 10, remove_parked: 10, add_parked: 10}\n")


if __name__ == "__main__":
    main()
