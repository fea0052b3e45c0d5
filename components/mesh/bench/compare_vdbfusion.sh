#!/usr/bin/env bash
# ltm's dense mesh beside VDBFusion (its KITTI settings, one thread) on the same scans and poses,
# both meshes scored by ltm_eval mesh against the same reference (issue 14's targets).
#
#   compare_vdbfusion.sh [--out-dir DIR] [--only REGEX] [--sim-frames N] [--sim-dir DIR]
#   ./ltm bench mesh_compare [the same arguments]
#
# Cases:
#   kitti-00 (scans 0:16), kitti-04, kitti-05, kitti-07 (scans 0:10): the shared KITTI snippets
#     at their SemanticKITTI poses. Both integrate the even scans (--every 2 --offset 0); both
#     meshes are scored on the same held-out points, the raw points of the odd scans within the
#     preset's range (written once by ltm_bench_mesh --heldout-out): c.med and c.p90 are the
#     median and 90th percentile of the held-out point to mesh distance. ltm at its hdl64 preset
#     (0.6 m voxels) and with --voxel 0.4. Skipped when the shared data is absent.
#   sim-site_loop: ltm_sim site_loop.yaml --frames 0:N (N = --sim-frames, default 600), written
#     once under the output folder (or an existing ltm_sim folder given by --sim-dir), poses.txt
#     (LiDAR frame), ltm with --preset vlp32; scored against the simulator's truth_mesh.ply
#     cropped to what was observed (ltm_bench_mesh --observed-out, points within 30 m of the
#     sensor; the same crop for both): F-score at 0.1 m, precision, recall, Chamfer-L1, and area
#     (mesh area / scored truth area: a double surface inflates it).
#   --out-dir DIR   meshes, held-out points, logs and table.txt (default: a new folder under /tmp)
#   --only REGEX    only the cases whose name matches
# Environment: LTM_BUILD_DIR (ltm's build, default ./build), LTM_SHARED_DATA (default
# shared/data next to the checkout), VDBFUSION_SOURCE, VDBFUSION_BUILD, VDBFUSION_GIT for peers/vdbfusion.sh
# (which builds VDBFusion outside the repository).
# VDBFusion: its examples/python/config/kitti.yaml (voxel 0.1 m, truncation 0.3 m, min weight 5,
# range 2.5..120 m, no space carving, no hole filling) with correct_scan off: it reads exactly the
# points ltm reads and the held-out points are raw.
# Time: wall clock, each program pinned to CPU 0 (taskset -c 0), one thread each (ltm's mesh
# threads=1, its default, given explicitly; VDBFusion's integration and meshing are single-threaded, the runner
# limits TBB to one thread). int = ltm's voxel map a scan (odometry local map at the given pose) /
# VDBFusion's Integrate a scan; mesh = ltm's signed distance + marching cubes of every local map +
# the global mesh / VDBFusion's ExtractTriangleMesh; all = int + mesh / scans.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
BUILD_DIR="${LTM_BUILD_DIR:-$ROOT/build}"
DATA="${LTM_SHARED_DATA:-$(dirname "$ROOT")/shared/data}"
OUT=""
ONLY=""
SIM_FRAMES=600
SIM_DIR=""
OBSERVED_RANGE=30

die() { printf 'compare_vdbfusion: error: %s\n' "$*" >&2; exit 1; }
say() { printf 'compare_vdbfusion: %s\n' "$*" >&2; }

while [ $# -gt 0 ]; do
    case "$1" in
        --out-dir) [ $# -ge 2 ] || die "--out-dir needs a folder"; OUT="$2"; shift 2 ;;
        --only) [ $# -ge 2 ] || die "--only needs a regular expression"; ONLY="$2"; shift 2 ;;
        --sim-frames)
            [ $# -ge 2 ] && [[ "$2" =~ ^[1-9][0-9]*$ ]] || die "--sim-frames needs a positive number"
            SIM_FRAMES="$2"; shift 2 ;;
        --sim-dir)
            [ $# -ge 2 ] && [ -f "$2/poses.txt" ] && [ -f "$2/truth_mesh.ply" ] ||
                die "--sim-dir needs a folder written by ltm_sim (poses.txt, truth_mesh.ply)"
            SIM_DIR="$2"; shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown option '$1' (--help)" ;;
    esac
done

BENCH="$BUILD_DIR/bin/ltm_bench_mesh"
EVAL="$BUILD_DIR/bin/ltm_eval"
SIMULATOR="$BUILD_DIR/bin/ltm_sim"
[ -x "$BENCH" ] && [ -x "$EVAL" ] || die "ltm_bench_mesh and ltm_eval are not built in $BUILD_DIR (./ltm setup)"
BENCH_HELP="$("$BENCH" --help 2>&1)" || true
for opt in --every --offset --frames --heldout-out --observed-out --observed-range --voxel; do
    [[ "$BENCH_HELP" == *" $opt "* ]] || die "$BENCH has no $opt option (rebuild it)"
done

# Cases: name|dir|poses|calib|frames|kind (kitti: held-out points; sim: truth mesh)
CASES=()
if [ -d "$DATA/kitti/sequences" ]; then
    for q in 00:16 04:10 05:10 07:10; do
        d="$DATA/kitti/sequences/${q%%:*}"
        [ -d "$d" ] || { say "no $d: skipped"; continue; }
        CASES+=("kitti-${q%%:*}|$d|$d/poses_semantickitti.txt|$d/calib.txt|0:${q##*:}|kitti")
    done
else
    say "no shared data at $DATA: the KITTI cases are skipped"
fi
CASES+=("sim-site_loop|${SIM_DIR:-}|poses.txt||0:$SIM_FRAMES|sim")

SELECTED=()
for c in "${CASES[@]}"; do
    name="${c%%|*}"
    [ -z "$ONLY" ] || [[ "$name" =~ $ONLY ]] || continue
    SELECTED+=("$c")
done
[ ${#SELECTED[@]} -gt 0 ] || { say "no cases to run"; exit 0; }
RUNNER="$("$HERE/peers/vdbfusion.sh" path)" || die "the VDBFusion peer could not be built (vdbfusion.sh above)"
PEER_COMMIT="$("$HERE/peers/vdbfusion.sh" commit)"
[ -n "$OUT" ] || OUT="$(mktemp -d /tmp/ltm-mesh-compare.XXXXXX)"
mkdir -p "$OUT"
command -v taskset > /dev/null || die "taskset (util-linux) is needed to pin both to one CPU"
PIN=(taskset -c 0)
LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"

# value LOG KEY: the number after KEY in an ltm_eval report ("-" when there is none).
value() {
    awk -v k="$2" '$1 == k {v = $NF} END {print (v == "" ? "-" : v)}' "$1"
}

# score NAME SYSTEM LOG MESH TRUTH [CROP]: scores MESH, then one row from LOG (the run's summary).
ROWS=()
score() {
    local name="$1" system="$2" log="$3" mesh="$4" truth="$5" crop="${6:-}" ev="${4%.ply}.eval"
    local scans int mesh_ms faces args=()
    if [[ "$system" == VDBFusion* ]]; then
        scans="$(sed -n 's/.*: \([0-9]*\) integrated$/\1/p' "$log" | head -1)"
        int="$(sed -n 's/.*integration ms a scan: mean \([0-9.]*\).*/\1/p' "$log")"
        mesh_ms="$(sed -n 's/^  meshing: \([0-9.]*\) ms.*/\1/p' "$log")"
    else
        scans="$(sed -n 's/.*, \([0-9]*\) integrated, .*/\1/p' "$log" | head -1)"
        int="$(sed -n 's/.*time a scan: voxel map \([0-9.]*\) ms.*/\1/p' "$log")"
        mesh_ms="$(awk '/^  meshing: / {a = $2; for (i = 1; i <= NF; ++i) if ($i == "global") g = $(i + 2)}
            END {if (a != "") print a + g}' "$log")"
    fi
    faces="$(sed -n 's/^  mesh: [0-9]* vertices, \([0-9]*\) faces.*/\1/p' "$log")"
    [ -n "$crop" ] && args=(--crop-to "$crop")
    if "$EVAL" mesh --mesh "$mesh" --truth "$truth" "${args[@]+"${args[@]}"}" > "$ev" 2>&1; then
        local all
        all="$(awk -v i="$int" -v m="$mesh_ms" -v n="$scans" 'BEGIN {printf "%.1f", i + m / n}')"
        ROWS+=("$name|$system|$scans|$(printf '%.1f' "$int")|$all|$(printf '%.0f' "$mesh_ms")|$faces|$(
            printf '%s|' "$(value "$ev" accuracy_median)" "$(value "$ev" completeness_median)" "$(value "$ev" completeness_p90)" \
                "$(value "$ev" fscore)" "$(value "$ev" precision)" "$(value "$ev" recall)" \
                "$(value "$ev" chamfer_l1)" "$(value "$ev" area_ratio)")")
    else
        say "$name: scoring $system failed: $(tail -1 "$ev")"
        ROWS+=("$name|$system|${scans:--}|fail||||||||||||")
    fi
}

# run NAME SYSTEM LOG COMMAND...: runs one system pinned to CPU 0; false (and says why) on failure.
run() {
    local name="$1" system="$2" log="$3"
    shift 3
    say "$name: $system"
    if "${PIN[@]}" "$@" > "$log" 2>&1; then return 0; fi
    say "$name: $system failed: $(grep -v '^mesh: ' "$log" | tail -1)"
    ROWS+=("$name|$system|-|fail||||||||||||")
    return 1
}

for c in "${SELECTED[@]}"; do
    IFS='|' read -r name dir poses calib frames kind <<< "$c"
    base="$OUT/$name"
    if [ "$kind" = sim ]; then
        if [ -z "$dir" ]; then
            dir="$OUT/sim_site_loop_$SIM_FRAMES"
            if [ ! -f "$dir/poses.txt" ] || [ ! -f "$dir/truth_mesh.ply" ]; then
                [ -x "$SIMULATOR" ] || die "ltm_sim is not built in $BUILD_DIR (./ltm setup)"
                say "simulating site_loop scans $frames into $dir"
                "$SIMULATOR" "$ROOT/components/simulator/scenarios/site_loop.yaml" --frames "$frames" \
                    --quiet --out "$dir" > "$OUT/sim_site_loop.log" 2>&1 ||
                    die "ltm_sim failed: $(tail -1 "$OUT/sim_site_loop.log")"
            fi
        fi
        poses="$dir/poses.txt"
        crop="$base.observed.ply"
        run "$name" "ltm vlp32" "$base.ltm.log" "$BENCH" "$dir" --poses "$poses" --preset vlp32 \
            --set threads=1 \
            --frames "$frames" --observed-out "$crop" --observed-range "$OBSERVED_RANGE" \
            --out "$base.ltm.ply" &&
            score "$name" "ltm vlp32" "$base.ltm.log" "$base.ltm.ply" "$dir/truth_mesh.ply" "$crop"
        [ -f "$crop" ] || { say "$name: no crop points from ltm: VDBFusion not scored"; continue; }
        run "$name" VDBFusion "$base.vdbfusion.log" "$RUNNER" "$dir" --poses "$poses" \
            --frames "$frames" --correct-scan 0 --out "$base.vdbfusion.ply" &&
            score "$name" VDBFusion "$base.vdbfusion.log" "$base.vdbfusion.ply" \
                "$dir/truth_mesh.ply" "$crop"
        continue
    fi
    held="$base.heldout.ply"
    common=("$dir" --poses "$poses" --calib "$calib" --frames "$frames" --every 2 --offset 0)
    run "$name" "ltm hdl64" "$base.ltm.log" "$BENCH" "${common[@]}" --set threads=1 --heldout-out "$held" \
        --out "$base.ltm.ply" && score "$name" "ltm hdl64" "$base.ltm.log" "$base.ltm.ply" "$held"
    [ -f "$held" ] || { say "$name: no held-out points from ltm: skipped"; continue; }
    run "$name" "ltm voxel 0.4" "$base.ltm_v04.log" "$BENCH" "${common[@]}" --set threads=1 --voxel 0.4 \
        --out "$base.ltm_v04.ply" &&
        score "$name" "ltm voxel 0.4" "$base.ltm_v04.log" "$base.ltm_v04.ply" "$held"
    run "$name" VDBFusion "$base.vdbfusion.log" "$RUNNER" "${common[@]}" --correct-scan 0 \
        --out "$base.vdbfusion.ply" &&
        score "$name" VDBFusion "$base.vdbfusion.log" "$base.vdbfusion.ply" "$held"
done

fmt='%-14s %-14s %5s %7s %7s %7s %8s %7s %7s %7s %6s %6s %6s %7s %6s\n'
num() { [[ "$1" =~ ^-?[0-9.]+(e[-+]?[0-9]+)?$ ]] && printf "%.${2}f" "$1" || printf '%s' "$1"; }
{
    printf "$fmt" case system scans "int ms" "all ms" "mesh ms" faces "a.med" "c.med" "c.p90" "F %" \
        "P %" "R %" "CD-L1" area
    for r in "${ROWS[@]+"${ROWS[@]}"}"; do
        IFS='|' read -r a b s i l m f am cm cp fs p rc cd ar _ <<< "$r"
        printf "$fmt" "$a" "$b" "$s" "$i" "$l" "$m" "$f" "$(num "$am" 4)" "$(num "$cm" 4)" "$(num "$cp" 3)" \
            "$(num "$fs" 1)" "$(num "$p" 1)" "$(num "$rc" 1)" "$(num "$cd" 3)" "$(num "$ar" 2)"
    done
    cat << EOF
VDBFusion ${PEER_COMMIT:0:7} at its KITTI settings (voxel 0.1 m, trunc 0.3 m, min weight 5, range 2.5..120 m),
correct_scan off: it integrates the same points as ltm. Time: wall clock, each on one thread
pinned to CPU 0 (taskset -c 0; ltm with --set threads=1, its default; load average $LOAD at
the start); int = ms a scan of ltm's voxel map / VDBFusion's Integrate; mesh = ms of all meshing
(ltm: every local map's signed distance + marching cubes + the global mesh; VDBFusion:
ExtractTriangleMesh); all = int + mesh / scans. a.med: mesh to reference; c.med, c.p90:
reference to mesh [m]. kitti-*: even scans integrated, the reference is the odd scans' raw points
(P: mesh samples within 0.1 m of a held-out point). sim-*: the reference is the truth mesh
cropped to 0.3 m around ltm's integrated points within $OBSERVED_RANGE m; F, P, R at 0.1 m [%];
CD-L1 [m]; area = the whole mesh's area / the scored (cropped) truth's area: a double surface
inflates it, and so does surface meshed beyond the crop.
EOF
} | tee "$OUT/table.txt"
printf '(logs, meshes, scores: %s)\n' "$OUT"
