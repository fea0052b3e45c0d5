#!/usr/bin/env bash
# Global localisation across two drives of one road (issue 27, item 4): a stretch of KITTI 00's
# real path through the simulator's town (sim_cases.py), driven twice in one world: session 0
# (every 5th pose, 4-6 m apart) makes a map at its true poses (ltm_bench_slam --poses, no
# registration); session 1 (every 2nd pose, 0-3 m to either side of the map's path) is localised
# alone on it, every --every-th scan as it came and turned by a random yaw (+-180 deg) and shifted
# up to 5 m (seed 1), with each sensor: OS1-64 (preset os1-64), HDL-64E (hdl64), VLP-32C (vlp32).
#   sim_cases.sh [--out-dir DIR] [--sensors "os1_64 hdl64e vlp32c"] [--frames 0:1500] [--every 5]
#                [--seeds "1"] [--world town|avenue] [--map-step 5]
# --world avenue: a road lined with trees and few buildings, the queries a day later with parked
# cars moved, removed and added; --map-step: the map keeps every Nth pose of the path.
#   ./ltm bench localise_sim [the same]
# Scans and maps are made once into DIR/<sensor>_<frames> and reused when there.
# Environment: LTM_BUILD_DIR (default ./build), LTM_SHARED_DATA (KITTI 00's poses; skipped with a
# message when absent).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
B="${LTM_BUILD_DIR:-$ROOT/build}/bin"
export LTM_SHARED_DATA="${LTM_SHARED_DATA:-$(dirname "$ROOT")/shared/data}"
OUT="" SENSORS="os1_64 hdl64e vlp32c" FRAMES="0:1500" EVERY=5 SEEDS="1" WORLD=town MAP_STEP=5
while [ $# -gt 0 ]; do
    case "$1" in
        --out-dir) OUT="$2"; shift 2 ;;
        --sensors) SENSORS="$2"; shift 2 ;;
        --frames) FRAMES="$2"; shift 2 ;;
        --every) EVERY="$2"; shift 2 ;;
        --seeds) SEEDS="$2"; shift 2 ;;
        --world) WORLD="$2"; shift 2 ;;
        --map-step) MAP_STEP="$2"; shift 2 ;;
        *) echo "sim_cases.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
if [ ! -f "$LTM_SHARED_DATA/kitti/poses/00.txt" ]; then
    echo "sim_cases.sh: no KITTI 00 poses under $LTM_SHARED_DATA (set LTM_SHARED_DATA): skipped"
    exit 0
fi
OUT="${OUT:-$(mktemp -d /tmp/ltm-localise-sim.XXXXXX)}"
mkdir -p "$OUT"
echo "results in $OUT"
preset_of() {
    case "$1" in
        os1_64) echo os1-64 ;; hdl64e) echo hdl64 ;; vlp32c) echo vlp32 ;; vlp16) echo vlp16 ;;
        *) echo "sim_cases.sh: no preset for sensor '$1'" >&2; exit 2 ;;
    esac
}
summary() {  # LOG
    echo "$(grep -E "^against" "$1"); $(grep -E "^time a scan" "$1"); $(grep -E "^cpu a scan" "$1")"
}
for sensor in $SENSORS; do
    preset="$(preset_of "$sensor")"
    dir="$OUT/${sensor}_${FRAMES/:/-}"
    [ "$WORLD" = town ] && [ "$MAP_STEP" = 5 ] || dir="${dir}_${WORLD}_step$MAP_STEP"
    if [ ! -f "$dir/map/map/manifest.txt" ]; then
        python3 "$HERE/sim_cases.py" "$dir" "$sensor" "${FRAMES%%:*}" "${FRAMES##*:}" \
            "$MAP_STEP" 2 "$WORLD"
        "$B/ltm_sim" "$dir/scenario.yaml" --session 0 --out "$dir/s0" --quiet
        "$B/ltm_sim" "$dir/scenario.yaml" --session 1 --out "$dir/s1" --quiet
        "$B/ltm_bench_slam" "$dir/s0" --poses "$dir/s0/poses.txt" --preset "$preset" \
            --out "$dir/map" > "$dir/map.log" 2>&1
    fi
    echo "$sensor (preset $preset, $WORLD), map of $(wc -l < "$dir/s0/poses.txt") scans, $(wc -l < "$dir/s1/poses.txt") query scans, every ${EVERY}th:"
    "$B/ltm_bench_localise" --map "$dir/map/map" "$dir/s1" --reference "$dir/s1/poses.txt" \
        --preset "$preset" --mode global --every "$EVERY" --out "$dir/asis.txt" \
        > "$dir/asis.log" 2>&1
    echo "  as it came: $(summary "$dir/asis.log")"
    for seed in $SEEDS; do
        "$B/ltm_bench_localise" --map "$dir/map/map" "$dir/s1" --reference "$dir/s1/poses.txt" \
            --preset "$preset" --mode global --every "$EVERY" --perturb-yaw 180 \
            --perturb-shift 5 --seed "$seed" --out "$dir/turned$seed.txt" > "$dir/turned$seed.log" 2>&1
        echo "  turned and shifted, seed $seed: $(summary "$dir/turned$seed.log")"
    done
done
