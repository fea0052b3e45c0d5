#!/usr/bin/env python3
"""The pose latency while a global localisation query runs (issue 28): a run's host.log lines
"global query for the scan at S s: T s (wall A to B): ..." (the localisation component's
`localisation/global` thread) against its probe.csv (every scan's and pose's stamp and the
writer's wall-clock source time). Prints a markdown section: the queries' times, and for the
scans published while a query ran and for the others, how many got a pose and the latency
scan -> pose (p50 / p99 / max).

    global_during.py HOST_LOG PROBE_CSV
"""
import csv
import re
import sys

QUERY = re.compile(r"global query for the scan at ([0-9.]+) s: ([0-9.]+) s "
                   r"\(wall ([0-9.]+) to ([0-9.]+)\): (.*)$")


def percentile(values, p):
    if not values:
        return float("nan")
    v = sorted(values)
    k = (len(v) - 1) * p / 100.0
    lo = int(k)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    queries = []
    with open(argv[1], errors="replace") as f:
        for line in f:
            m = QUERY.search(line)
            if m:
                queries.append((float(m.group(3)), float(m.group(4)), float(m.group(2)),
                                m.group(5) == "localised"))
    scans, poses = {}, {}
    with open(argv[2]) as f:
        for row in csv.DictReader(f):
            topic = row["topic"]
            stamp = round(float(row["stamp"]), 6)
            if topic.endswith("points"):
                scans[stamp] = float(row["sent"])
            elif topic.endswith("pose"):
                poses.setdefault(stamp, float(row["sent"]))
    print("\n## global localisation off the tracking thread (host.log, probe.csv)\n")
    if not queries:
        print("no global query ran (`localisation/global` logged none)")
        return 0
    times = [q[2] for q in queries]
    print(f"{len(queries)} global queries ({sum(q[3] for q in queries)} localised): "
          f"time p50 {1000 * percentile(times, 50):.0f} ms, max {1000 * max(times):.0f} ms, "
          f"{sum(times):.1f} s in all\n")
    spans = sorted((q[0], q[1]) for q in queries)

    def during(t):
        return any(a <= t <= b for a, b in spans)

    print("| scans published | scans | with a pose | scan -> pose p50 / p99 / max |")
    print("|---|---:|---:|---|")
    for label, want in (("while a query ran", True), ("otherwise", False)):
        lat, n, with_pose = [], 0, 0
        for stamp, sent in scans.items():
            if during(sent) != want:
                continue
            n += 1
            if stamp in poses:
                with_pose += 1
                lat.append(1000 * (poses[stamp] - sent))
        if lat:
            figures = (f"{percentile(lat, 50):.0f} / {percentile(lat, 99):.0f} / "
                       f"{max(lat):.0f} ms")
        else:
            figures = "-"
        print(f"| {label} | {n} | {with_pose} | {figures} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
