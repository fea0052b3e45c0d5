#!/usr/bin/env bash
# Map maintenance on the shared real data (issue 13's KITTI targets): each SemanticKITTI snippet
# (00, 04, 05, 07; one session of 10 labelled scans at its SemanticKITTI poses) through
# ltm_bench_maintenance with its defaults (no preset: the thresholds follow the window's span and
# views), scored by ltm_eval dynamic (50 m range, 0.05 m matching):
# SA, DA, AA, and DA over the objects that travel at least 1 m; then the score of a perfect
# cleaned map (--write-static) for reference.
#   real_data.sh [--out-dir DIR] [--set KEY=VALUE ...]
#   ./ltm bench maintenance_real [--out-dir DIR] [--set KEY=VALUE ...]   (--set: a maintenance key
#   for ltm_bench_maintenance, e.g. change.voxel_score=0.5)
# Environment: LTM_BUILD_DIR (default ./build), LTM_SHARED_DATA (default shared/data next to the checkout;
# skipped with a message when absent).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
B="${LTM_BUILD_DIR:-$ROOT/build}/bin"
DATA="${LTM_SHARED_DATA:-$(dirname "$ROOT")/shared/data}"
OUT=""
SETS=()
while [ $# -gt 0 ]; do
    case "$1" in
        --out-dir) OUT="$2"; shift 2 ;;
        --set) SETS+=(--set "$2"); shift 2 ;;
        *) echo "real_data.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
K="$DATA/kitti/sequences"
if [ ! -d "$K" ]; then
    echo "real_data.sh: no KITTI snippets under $DATA (set LTM_SHARED_DATA): skipped"
    exit 0
fi
OUT="${OUT:-$(mktemp -d /tmp/ltm-maintenance-real.XXXXXX)}"
mkdir -p "$OUT"
echo "results in $OUT (KITTI / SemanticKITTI: CC BY-NC-SA 3.0, see $DATA/README*)"
printf '%-4s %8s %8s %8s %10s   %s\n' seq SA DA AA "DA>=1m" "(perfect map: DA, DA>=1m)"
for s in 00 04 05 07; do
    [ -d "$K/$s/labels" ] || continue
    "$B/ltm_bench_maintenance" --sessions "$K/$s" --poses "$K/$s/poses_semantickitti.txt" \
        --calib "$K/$s/calib.txt" "${SETS[@]}" --out "$OUT/kitti_$s" > "$OUT/kitti_$s.log" 2>&1
    args=(--scans "$K/$s" --label-scheme semantickitti --poses "$K/$s/poses_semantickitti.txt"
          --poses-frame camera --calib "$K/$s/calib.txt" --max-range 50)
    "$B/ltm_eval" dynamic "${args[@]}" --map "$OUT/kitti_$s/cleaned_map.ply" \
        --out "$OUT/eval_$s" > "$OUT/eval_$s.txt" 2>/dev/null
    "$B/ltm_eval" dynamic "${args[@]}" --write-static "$OUT/perfect_$s.ply" > /dev/null 2>&1
    "$B/ltm_eval" dynamic "${args[@]}" --map "$OUT/perfect_$s.ply" > "$OUT/perfect_$s.txt" 2>/dev/null
    field() { grep -E "^  $1 " "$2" | head -1 | awk '{print $NF}'; }
    moving() { sed -n '/\[moving_objects\]/,$p' "$1" | grep -E '^  DA \[' | awk '{print $NF}'; }
    printf '%-4s %8.2f %8.2f %8.2f %10.2f   (%.2f, %.2f)\n' "$s" \
        "$(field 'SA \[%\]' "$OUT/eval_$s.txt")" "$(field 'DA \[%\]' "$OUT/eval_$s.txt")" \
        "$(field 'AA \[%\]' "$OUT/eval_$s.txt")" "$(moving "$OUT/eval_$s.txt")" \
        "$(field 'DA \[%\]' "$OUT/perfect_$s.txt")" "$(moving "$OUT/perfect_$s.txt")"
done
