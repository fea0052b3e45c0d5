#!/usr/bin/env bash
# Global localisation on ltm's own many-lap maps (issue 26, item 6): site_loop driven N times,
#   a SLAM map (ltm_bench_slam --scenario --laps N: odometry, loops, the long-term folding) and a
#   map of the same scans at their true poses (--true-poses), then another day's scans (site_loop's
#   second session) localised alone on each: every --every-th scan turned by a random yaw (+-180
#   deg) and shifted up to 5 m (as localise_real), 3 seeds; and every 40th scan as it came.
#   multilap.sh [--laps "3 5"] [--every 10] [--seeds "1 2 3"] [--out-dir DIR]
#   ./ltm bench localise_multilap [the same]
# Maps are built once into DIR/slam_N and DIR/truth_N (minutes a lap) and reused when there; the
# scans' true poses are put in each map's frame by the SE(3) alignment of its ATE
# (T_map_reference.txt, written by ltm_bench_slam).
# Environment: LTM_BUILD_DIR (default ./build).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
B="${LTM_BUILD_DIR:-$ROOT/build}/bin"
SCENARIO="$ROOT/components/simulator/scenarios/site_loop.yaml"
LAPS="3 5" EVERY=10 SEEDS="1 2 3" OUT=""
while [ $# -gt 0 ]; do
    case "$1" in
        --laps) LAPS="$2"; shift 2 ;;
        --every) EVERY="$2"; shift 2 ;;
        --seeds) SEEDS="$2"; shift 2 ;;
        --out-dir) OUT="$2"; shift 2 ;;
        *) echo "multilap.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
OUT="${OUT:-$(mktemp -d /tmp/ltm-localise-multilap.XXXXXX)}"
mkdir -p "$OUT"
echo "results in $OUT"
DAY="$OUT/another_day"
if [ ! -f "$DAY/poses.txt" ]; then
    "$B/ltm_sim" "$SCENARIO" --session 1 --out "$DAY" --quiet
fi
localise() {  # MAP_DIR TRANSFORM LOG [options]
    local map="$1" transform="$2" log="$3"
    shift 3
    "$B/ltm_bench_localise" --map "$map" "$DAY" --reference "$DAY/poses.txt" \
        --reference-transform "$transform" --preset vlp32 --mode global "$@" > "$log" 2>&1
    echo "$(grep -E '^against' "$log"); $(grep -E '^error of' "$log" | sed 's/error of the right ones: //'); $(grep -E '^time a scan' "$log")"
}

for n in $LAPS; do
    for kind in slam truth; do
        dir="$OUT/${kind}_$n"
        if [ ! -f "$dir/map/manifest.txt" ]; then
            extra=()
            [ "$kind" = truth ] && extra=(--true-poses)
            "$B/ltm_bench_slam" --scenario "$SCENARIO" --laps "$n" --preset vlp32 "${extra[@]}" \
                --out "$dir" > "$dir.log" 2>&1
        fi
    done
    echo "site_loop, $n laps: $(grep -E '^(ATE|keyframes)' "$OUT/slam_$n.log" | tr '\n' ' ')"
    for kind in slam truth; do
        dir="$OUT/${kind}_$n"
        echo "  $kind map ($(grep -E '^keyframes' "$dir.log" | cut -d';' -f1)):"
        echo "    every 40th scan as it came: $(localise "$dir/map" "$dir/T_map_reference.txt" "$dir/every40.log" --every 40)"
        for seed in $SEEDS; do
            echo "    every ${EVERY}th, turned and shifted, seed $seed: $(localise "$dir/map" "$dir/T_map_reference.txt" "$dir/seed$seed.log" --every "$EVERY" --perturb-yaw 180 --perturb-shift 5 --seed "$seed")"
        done
    done
done
