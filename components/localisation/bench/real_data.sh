#!/usr/bin/env bash
# Global localisation on the shared real data (issue 12's real-data targets):
#   KITTI snippets 00, 04, 05, 07: a map from the frames at their SemanticKITTI poses
#     (ltm_bench_slam --poses, no registration), then every frame turned by a random yaw
#     (+-180 deg) and shifted up to 5 m, localised alone on it (3 seeds);
#   hku-avia-2session: a map from session 1 at its odometry poses (preset narrow), then every
#     scan of session 2 localised alone on it, scored against T_s1_s2 x session-2 odometry and,
#     for the scans of the cross-session pairs, against the pairs' ICP-refined poses
#     (hku_score.py: verified pairs, and the others that view the same place).
#   real_data.sh [--out-dir DIR]        ./ltm bench localise_real [--out-dir DIR]
# Maps already in DIR (a previous run's) are reused.
# Environment: LTM_BUILD_DIR (default ./build), LTM_SHARED_DATA (default shared/data next to the checkout;
# skipped with a message when absent).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
B="${LTM_BUILD_DIR:-$ROOT/build}/bin"
DATA="${LTM_SHARED_DATA:-$(dirname "$ROOT")/shared/data}"
OUT=""
while [ $# -gt 0 ]; do
    case "$1" in
        --out-dir) OUT="$2"; shift 2 ;;
        *) echo "real_data.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
if [ ! -d "$DATA/kitti/sequences" ] && [ ! -d "$DATA/hku-avia-2session" ]; then
    echo "real_data.sh: no shared data under $DATA (set LTM_SHARED_DATA): skipped"
    exit 0
fi
OUT="${OUT:-$(mktemp -d /tmp/ltm-localise-real.XXXXXX)}"
mkdir -p "$OUT"
echo "results in $OUT"
K="$DATA/kitti/sequences"
for s in 00 04 05 07; do
    [ -d "$K/$s" ] || continue
    [ -f "$OUT/kitti_$s/map/manifest.txt" ] ||
        "$B/ltm_bench_slam" "$K/$s" --poses "$K/$s/poses_semantickitti.txt" --calib "$K/$s/calib.txt" \
            --preset hdl64 --out "$OUT/kitti_$s" > "$OUT/kitti_map_$s.log" 2>&1
    for seed in 1 2 3; do
        "$B/ltm_bench_localise" --map "$OUT/kitti_$s/map" "$K/$s" --reference "$OUT/kitti_$s/slam.txt" \
            --preset hdl64 --mode global --perturb-yaw 180 --perturb-shift 5 --seed "$seed" \
            --out "$OUT/kitti_${s}_seed$seed.txt" > "$OUT/kitti_${s}_seed$seed.log" 2>&1
        echo "KITTI $s, seed $seed: $(grep -E '^against' "$OUT/kitti_${s}_seed$seed.log");" \
            "$(grep -E '^time a scan' "$OUT/kitti_${s}_seed$seed.log");" \
            "$(grep -E '^cpu a scan' "$OUT/kitti_${s}_seed$seed.log")"
    done
done
H="$DATA/hku-avia-2session"
if [ -d "$H" ]; then
    [ -f "$OUT/hku_s1/map/manifest.txt" ] ||
        "$B/ltm_bench_slam" "$H/session1" --preset narrow --poses "$H/session1/odom_poses.txt" \
            --out "$OUT/hku_s1" > "$OUT/hku_map.log" 2>&1
    "$B/ltm_bench_localise" --map "$OUT/hku_s1/map" "$H/session2" --reference "$H/session2/odom_poses.txt" \
        --reference-transform "$H/T_s1_s2.txt" --preset narrow --mode global \
        --out "$OUT/hku_global.txt" > "$OUT/hku_global.log" 2>&1
    echo "hku session 2 on session 1's map:"
    grep -E '^(against|error|time a scan|cpu a scan)' "$OUT/hku_global.log" | sed 's/^/  /'
    HKU_DATA="$H" python3 "$HERE/hku_score.py" "$OUT/hku_global.txt" | sed 's/^/  /'
fi
