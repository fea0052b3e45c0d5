#!/usr/bin/env python3
"""Each day's final SLAM keyframes of a `./ltm bench lifelong` run against the truth, split into
ground first driven that day (new ground: the true position more than --radius from every earlier
day's true path, as `ltm_eval lifelong`'s new-ground column) and ground driven on an earlier day.

A day's `slam_tum.txt` holds its keyframes as the site's version after the day keeps them (the
lifelong mode never moves an earlier day's keyframes: `shift_max_m 0` in every version.txt), so
this says how far the map of new ground is from the truth, day by day. Positions are planar (x, y):
the one alignment is fitted on day 0's keyframes, rigid (as the benchmark's) and with one scale
(the map's scale, which no loop observes: `ltm_eval lifelong`'s "with scale" lines).

Usage: keyframes_by_ground.py RUN --days N [--radius 10]
RUN/dayN/ holds slam_tum.txt and truth/poses_tum.txt (or ground_truth_tum.txt).
"""
import argparse
import math
import os
import sys


def read_tum(path):
    poses = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            a = line.split()
            if len(a) < 4:
                sys.exit(f"keyframes_by_ground: {path}: a line with fewer than 4 columns")
            poses[round(float(a[0]), 2)] = (float(a[1]), float(a[2]))
    return poses


def truth_file(day_dir):
    for name in ("truth/poses_tum.txt", "ground_truth_tum.txt"):
        if os.path.exists(os.path.join(day_dir, name)):
            return os.path.join(day_dir, name)
    sys.exit(f"keyframes_by_ground: {day_dir}: no truth/poses_tum.txt or ground_truth_tum.txt")


def fit(est, ref):
    """Planar Umeyama: rotation, translation and scale mapping est onto ref (lists of (x, y))."""
    n = len(est)
    me = [sum(p[i] for p in est) / n for i in (0, 1)]
    mr = [sum(q[i] for q in ref) / n for i in (0, 1)]
    a = b = var = 0.0
    for p, q in zip(est, ref):
        px, py, qx, qy = p[0] - me[0], p[1] - me[1], q[0] - mr[0], q[1] - mr[1]
        a += px * qx + py * qy
        b += px * qy - py * qx
        var += px * px + py * py
    return me, mr, math.atan2(b, a), math.hypot(a, b) / var


def apply(t, p, scaled):
    me, mr, th, s = t
    s = s if scaled else 1.0
    c, sn = math.cos(th), math.sin(th)
    x, y = p[0] - me[0], p[1] - me[1]
    return (s * (c * x - sn * y) + mr[0], s * (sn * x + c * y) + mr[1])


def rms(v):
    return math.sqrt(sum(e * e for e in v) / len(v)) if v else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--days", type=int, required=True)
    ap.add_argument("--radius", type=float, default=10.0, help="new ground: farther than this [m]")
    o = ap.parse_args()
    day = [os.path.join(o.run, f"day{d}") for d in range(o.days)]
    for d in day:
        if not os.path.exists(os.path.join(d, "slam_tum.txt")):
            sys.exit(f"keyframes_by_ground: no {d}/slam_tum.txt (--days too many?)")
    kf0, truth0 = read_tum(os.path.join(day[0], "slam_tum.txt")), read_tum(truth_file(day[0]))
    stamps = [k for k in kf0 if k in truth0]
    if len(stamps) < 3:
        sys.exit("keyframes_by_ground: fewer than 3 of day 0's keyframes match the truth by stamp")
    t = fit([kf0[k] for k in stamps], [truth0[k] for k in stamps])
    print(f"the one alignment on day 0's {len(stamps)} keyframes; with scale: the map is "
          f"{100.0 * (1.0 / t[3] - 1.0):+.3f} % against the truth")
    print("day ground        keyframes  rigid: rmse    max  | scale fitted: rmse    max")
    earlier = []  # every 5th true position of the days before
    cell = o.radius
    for d in range(o.days):
        kf, truth = read_tum(os.path.join(day[d], "slam_tum.txt")), read_tum(truth_file(day[d]))
        grid = {}
        for p in earlier:
            grid.setdefault((int(p[0] // cell), int(p[1] // cell)), []).append(p)

        def is_new(p):
            i, j = int(p[0] // cell), int(p[1] // cell)
            for di in (-1, 0, 1):
                for dj in (-1, 0, 1):
                    for q in grid.get((i + di, j + dj), []):
                        if math.dist(p, q) <= o.radius:
                            return False
            return True

        split = {"new": ([], []), "driven before": ([], [])}
        for k, p in kf.items():
            if k not in truth:
                continue
            g = truth[k]
            rigid, scaled = split["new" if is_new(g) else "driven before"]
            rigid.append(math.dist(apply(t, p, False), g))
            scaled.append(math.dist(apply(t, p, True), g))
        for name, (rigid, scaled) in split.items():
            if rigid:
                print(f"{d:3d} {name:14s} {len(rigid):9d}  {rms(rigid):11.3f} {max(rigid):6.3f}  | "
                      f"{rms(scaled):18.3f} {max(scaled):6.3f}")
        earlier += [truth[k] for k in sorted(truth)[::5]]


if __name__ == "__main__":
    main()
