#!/usr/bin/env bash
# ltm's odometry beside KISS-ICP (default settings, one thread) on the hard cases of issue 11:
# the same scans, both scored by ltm_eval traj against the same reference lines.
#
#   compare_hard_cases.sh [--out-dir DIR] [--max-frames N] [--kiss-kitti-correction] [--sim]
#                         [--observe [--cases-dir DIR] [--kitti00-frames N]]
#                         [--only REGEX] [DIR:PRESET[:N[,N...]] ...]
#   ./ltm bench hard_cases [the same arguments]
#
# Cases: hku-avia session 1 and 2 (preset narrow) keeping every 2nd, 3rd and 5th scan; KITTI
# snippets 00, 04, 05, 07 (preset hdl64) keeping every scan, every 2nd and every 3rd; and every
# DIR:PRESET given (e.g. a folder written by `./ltm sim`, KITTI layout with poses.txt in the LiDAR
# frame), all scans or every Nth for each N listed. The reference is DIR/poses.txt or
# DIR/odom_poses.txt (LiDAR frame) or DIR/poses_semantickitti.txt with DIR/calib.txt (camera
# frame), its lines 1, 1+N, 1+2N, ... as many as scans were kept.
#   --sim              also the simulated hard cases, written first by ltm_sim --format pcd (raw
#                      sweeps with per-point time) under the output folder: fast_turns with
#                      livox_avia (preset narrow) and vlp16, turn_on_spot with vlp16 and
#                      livox_avia (narrow); all scans and every 2nd
#   --observe          also issue 27's cases (large steps along weakly constrained directions),
#                      simulated first (KITTI layout) into the cases folder when missing:
#                      tree_road (components/simulator/scenarios: a straight country road with
#                      sparse trees, 10-15 m/s) with os1_64 (preset os1-64) and vlp16, every 5th
#                      and 10th scan; corridor (placed walls, VLP-16 walking) all, every 5th, 10th;
#                      the first N scans of kitti00_path (HDL-64E on KITTI 00's path), every 5th
#                      and 10th
#   --cases-dir DIR    where --observe's simulated cases are (default: OUT/sim)
#   --kitti00-frames N scans of kitti00_path simulated (default 1500, 1.2 km; 4541: all of it)
#   --out-dir DIR      poses, logs and table.txt (default: a new folder under /tmp)
#   --reuse-peer       keep KISS-ICP's poses and log of an earlier run in the same --out-dir
#                      (ltm runs again; KISS-ICP's results do not change with ltm's)
#   --max-frames N     only the first N kept scans of each case
#   --only REGEX       only the cases whose name matches
#   --kiss-kitti-correction  give KISS-ICP's runner the KITTI vertical-angle correction its KITTI
#                      loader applies (off: both systems read exactly the same points)
# Environment: LTM_BUILD_DIR (ltm's build, default ./build), LTM_SHARED_DATA (default
# shared/data next to the checkout; the shared cases are skipped when it is absent), and KISS_ICP_SOURCE,
# SOPHUS_SOURCE, KISS_ICP_BUILD for kiss_icp.sh (which builds KISS-ICP outside the repository).
# Columns: ATE = RMSE of the SE(3)-aligned absolute trajectory error [m]; path = path length over
# the reference's [%]; ltm deg = scans ltm flagged degenerate (pose along a weak direction from its
# motion model); ltm off = scans ltm reported registered while > 1 m off the reference step; 3sig =
# step errors within 3 sigma of ltm's published covariance [%]; ltm trk/lost = scans
# ltm registered / not (its "tracking:" line; from its frame states when it has none:
# initialised + tracked + recovered / lost, "+K" other states); ltm lost = its longest lost
# stretch [s of sensor time]; fps = frames a second by CPU time of the odometry thread, one
# thread each (file reading excluded).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../../.." && pwd)"
BUILD_DIR="${LTM_BUILD_DIR:-$ROOT/build}"
DATA="${LTM_SHARED_DATA:-$(dirname "$ROOT")/shared/data}"
OUT=""
MAX_FRAMES=0
ONLY=""
KISS_EXTRA=()
EXTRA=()
SIM=0
OBSERVE=0
REUSE_PEER=0
CASES_DIR=""
KITTI00_FRAMES=1500

die() { printf 'compare_hard_cases: error: %s\n' "$*" >&2; exit 1; }
say() { printf 'compare_hard_cases: %s\n' "$*" >&2; }

while [ $# -gt 0 ]; do
    case "$1" in
        --out-dir) [ $# -ge 2 ] || die "--out-dir needs a folder"; OUT="$2"; shift 2 ;;
        --max-frames)
            [ $# -ge 2 ] && [[ "$2" =~ ^[0-9]+$ ]] || die "--max-frames needs a number"
            MAX_FRAMES="$2"; shift 2 ;;
        --only) [ $# -ge 2 ] || die "--only needs a regular expression"; ONLY="$2"; shift 2 ;;
        --kiss-kitti-correction) KISS_EXTRA+=(--kitti-correction); shift ;;
        --sim) SIM=1; shift ;;
        --observe) OBSERVE=1; shift ;;
        --reuse-peer) REUSE_PEER=1; shift ;;
        --cases-dir) [ $# -ge 2 ] || die "--cases-dir needs a folder"; CASES_DIR="$2"; shift 2 ;;
        --kitti00-frames)
            [ $# -ge 2 ] && [[ "$2" =~ ^[1-9][0-9]*$ ]] || die "--kitti00-frames needs a number"
            KITTI00_FRAMES="$2"; shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        -*) die "unknown option '$1' (--help)" ;;
        *:*) EXTRA+=("$1"); shift ;;
        *) die "'$1': extra cases are DIR:PRESET or DIR:PRESET:N[,N...]" ;;
    esac
done

BENCH="$BUILD_DIR/bin/ltm_bench_odometry"
EVAL="$BUILD_DIR/bin/ltm_eval"
[ -x "$BENCH" ] && [ -x "$EVAL" ] || die "ltm_bench_odometry and ltm_eval are not built in $BUILD_DIR (./ltm setup)"

# Cases: name|dir|preset|every|reference|reference frame|calib
CASES=()
if [ -d "$DATA" ]; then
    for s in 1 2; do
        d="$DATA/hku-avia-2session/session$s"
        [ -d "$d" ] || { say "no $d: skipped"; continue; }
        for n in 2 3 5; do CASES+=("hku-s$s/$n|$d|narrow|$n|$d/odom_poses.txt|lidar|"); done
    done
    for q in 00 04 05 07; do
        d="$DATA/kitti/sequences/$q"
        [ -d "$d" ] || { say "no $d: skipped"; continue; }
        for n in 1 2 3; do
            CASES+=("kitti-$q/$n|$d|hdl64|$n|$d/poses_semantickitti.txt|camera|$d/calib.txt")
        done
    done
else
    say "no shared data at $DATA: the hku-avia and KITTI cases are skipped"
fi
if [ "$SIM" = 1 ]; then
    [ -n "$OUT" ] || OUT="$(mktemp -d /tmp/ltm-hard-cases.XXXXXX)"
    mkdir -p "$OUT/sim"
    SIMULATOR="$BUILD_DIR/bin/ltm_sim"
    [ -x "$SIMULATOR" ] || die "ltm_sim is not built in $BUILD_DIR (./ltm setup)"
    for s in fast_turns:livox_avia:narrow fast_turns:vlp16:vlp16 turn_on_spot:vlp16:vlp16 \
        turn_on_spot:livox_avia:narrow; do
        IFS=: read -r scenario sensor preset <<< "$s"
        d="$OUT/sim/${scenario}_$sensor"
        if [ ! -f "$d/poses.txt" ]; then
            say "simulating $scenario with $sensor into $d"
            "$SIMULATOR" "$ROOT/components/simulator/scenarios/$scenario.yaml" --sensor "$sensor" \
                --format pcd --quiet --out "$d" > "$OUT/sim_${scenario}_$sensor.log" 2>&1 ||
                die "ltm_sim failed: $(tail -1 "$OUT/sim_${scenario}_$sensor.log")"
        fi
        EXTRA+=("$d:$preset:1,2")
    done
fi
if [ "$OBSERVE" = 1 ]; then
    [ -n "$OUT" ] || OUT="$(mktemp -d /tmp/ltm-hard-cases.XXXXXX)"
    [ -n "$CASES_DIR" ] || CASES_DIR="$OUT/sim"
    mkdir -p "$CASES_DIR"
    SIMULATOR="$BUILD_DIR/bin/ltm_sim"
    [ -x "$SIMULATOR" ] || die "ltm_sim is not built in $BUILD_DIR (./ltm setup)"
    # scenario:sensor:preset:everys:frames
    for s in tree_road:os1_64:os1-64:5,10: tree_road:vlp16:vlp16:5,10: corridor:vlp16:vlp16:1,5,10: \
        "kitti00_path:hdl64e:hdl64:5,10:$KITTI00_FRAMES"; do
        IFS=: read -r scenario sensor preset everys frames <<< "$s"
        d="$CASES_DIR/${scenario}_$sensor${frames:+_$frames}"
        if [ ! -f "$d/poses.txt" ]; then
            say "simulating $scenario with $sensor into $d"
            args=(--sensor "$sensor")
            [ -n "$frames" ] && args+=(--frames "0:$frames")
            "$SIMULATOR" "$ROOT/components/simulator/scenarios/$scenario.yaml" "${args[@]}" \
                --quiet --out "$d" > "$OUT/sim_${scenario}_$sensor.log" 2>&1 ||
                die "ltm_sim failed: $(tail -1 "$OUT/sim_${scenario}_$sensor.log")"
        fi
        EXTRA+=("$d:$preset:$everys")
    done
fi
for e in "${EXTRA[@]+"${EXTRA[@]}"}"; do
    IFS=: read -r d preset everys <<< "$e"
    [ -d "$d" ] || die "extra case '$e': $d is not a folder"
    [ -n "$preset" ] || die "extra case '$e': no preset"
    ref="" frame=lidar calib=""
    if [ -f "$d/poses.txt" ]; then ref="$d/poses.txt"
    elif [ -f "$d/odom_poses.txt" ]; then ref="$d/odom_poses.txt"
    elif [ -f "$d/poses_semantickitti.txt" ] && [ -f "$d/calib.txt" ]; then
        ref="$d/poses_semantickitti.txt" frame=camera calib="$d/calib.txt"
    fi
    IFS=, read -r -a ns <<< "${everys:-1}"
    for n in "${ns[@]}"; do
        [[ "$n" =~ ^[1-9][0-9]*$ ]] || die "extra case '$e': '$n' is not a positive number"
        CASES+=("$(basename "$d")/$n|$d|$preset|$n|$ref|$frame|$calib")
    done
done
[ ${#CASES[@]} -gt 0 ] || { say "no cases to run"; exit 0; }
RUNNER="$("$HERE/kiss_icp.sh" path)" || die "the KISS-ICP peer could not be built (kiss_icp.sh above)"
[ -n "$OUT" ] || OUT="$(mktemp -d /tmp/ltm-hard-cases.XXXXXX)"
mkdir -p "$OUT"
BENCH_HAS_EVERY=0
"$BENCH" --help 2>&1 | grep -q -- "--every" && BENCH_HAS_EVERY=1

# A folder of symbolic links to every Nth scan (with times.txt and calib.txt), for an
# ltm_bench_odometry without --every.
subsample_dir() {
    local src="$1" n="$2" dst="$3" sub="" f i=0 k=0
    rm -rf "$dst"
    if [ -d "$src/velodyne" ]; then sub=velodyne; elif [ -d "$src/Scans" ]; then sub=Scans; fi
    mkdir -p "$dst/$sub"
    for f in "$src/$sub"/*; do  # globs expand sorted
        case "$f" in *.bin|*.pcd|*.ply) ;; *) continue ;; esac
        if [ $((i % n)) -eq 0 ]; then
            ln -s "$f" "$dst/$sub/$(printf '%06d' $k).${f##*.}"
            k=$((k + 1))
        fi
        i=$((i + 1))
    done
    [ -f "$src/times.txt" ] && awk -v n="$n" '(NR - 1) % n == 0' "$src/times.txt" > "$dst/times.txt"
    [ -f "$src/calib.txt" ] && ln -s "$src/calib.txt" "$dst/calib.txt"
    return 0
}

# ate ESTIMATE FRAME CALIB REFERENCE_LINES: the aligned ATE RMSE, "-" without a reference.
ate() {
    local est="$1" frame="$2" calib="$3" sub="$4" args=()
    [ -s "$sub" ] && [ -s "$est" ] || { echo "-"; return; }
    [ -n "$calib" ] && args+=(--reference-frame "$frame" --calib "$calib")
    "$EVAL" traj --estimate "$est" --reference "$sub" "${args[@]}" > "$est.eval" 2>&1 ||
        { echo "fail"; return; }
    awk '/^\[ate_se3_aligned\]/ {s = 1} s && /rmse/ {printf "%.3f", $NF; exit}' "$est.eval"
}

# path_length POSES: the length of a KITTI-format trajectory [m].
path_length() {
    awk '{ if (NR > 1) s += sqrt(($4 - x) ^ 2 + ($8 - y) ^ 2 + ($12 - z) ^ 2); x = $4; y = $8; z = $12 }
         END { printf "%.3f", s }' "$1"
}
# path_pct ESTIMATE REFERENCE_LINES: the estimate's path over the reference's [%] ("-": unknown).
path_pct() {
    [ -s "$1" ] && [ -s "$2" ] || { echo "-"; return; }
    local e r
    e="$(path_length "$1")" r="$(path_length "$2")"
    awk -v e="$e" -v r="$r" 'BEGIN { if (r > 0) printf "%.1f", 100 * e / r; else print "-" }'
}

ROWS=()
for c in "${CASES[@]}"; do
    IFS='|' read -r name dir preset every ref frame calib <<< "$c"
    [ -z "$ONLY" ] || [[ "$name" =~ $ONLY ]] || continue
    tag="${name//\//_every}"
    say "$name: $dir, preset $preset, every $every"
    lim=()
    [ "$MAX_FRAMES" -gt 0 ] && lim=(--max-frames "$MAX_FRAMES")

    # KISS-ICP first: it reports how many scans were kept.
    kiss_fps="fail" kiss_ate="fail" kept=0
    if [ "$REUSE_PEER" = 1 ] && [ -s "$OUT/$tag.kiss.txt" ] &&
        grep -q '^speed by CPU time' "$OUT/$tag.kiss.log" 2>/dev/null; then
        kept="$(awk '/^frames:/ {gsub(";", "", $2); print $2; exit}' "$OUT/$tag.kiss.log")"
        kiss_fps="$(awk '/^speed by CPU time/ {print $(NF-5); exit}' "$OUT/$tag.kiss.log")"
    elif "$RUNNER" "$dir" --every "$every" "${lim[@]+"${lim[@]}"}" --out "$OUT/$tag.kiss.txt" \
        "${KISS_EXTRA[@]+"${KISS_EXTRA[@]}"}" > "$OUT/$tag.kiss.log" 2>&1; then
        kept="$(awk '/^frames:/ {gsub(";", "", $2); print $2; exit}' "$OUT/$tag.kiss.log")"
        kiss_fps="$(awk '/^speed by CPU time/ {print $(NF-5); exit}' "$OUT/$tag.kiss.log")"
    else
        say "$name: KISS-ICP failed: $(tail -1 "$OUT/$tag.kiss.log")"
    fi
    kept="${kept:-0}"
    sub="$OUT/$tag.reference.txt"
    rm -f "$sub"
    if [ -n "$ref" ]; then
        # Lines 1, 1+N, ...: as many as scans were kept (all of them if that is unknown).
        awk -v n="$every" -v k="$kept" '(NR - 1) % n == 0 { print; if (++c == k) exit }' \
            "$ref" > "$sub"
    fi
    [ "$kiss_fps" = fail ] || kiss_ate="$(ate "$OUT/$tag.kiss.txt" "$frame" "$calib" "$sub")"

    kiss_path="$(path_pct "$OUT/$tag.kiss.txt" "$sub")"
    ltm_fps="fail" ltm_ate="fail" ltm_track="fail" ltm_longest="-" ltm_path="-"
    ltm_deg="-" ltm_off="-" ltm_3sig="-"
    ltm_ref=()
    if [ -n "$ref" ]; then
        ltm_ref=(--reference "$ref")
        [ -n "$calib" ] && ltm_ref+=(--calib "$calib")
    fi
    ltm_dir="$dir" ltm_every=()
    if [ "$every" -gt 1 ]; then
        if [ "$BENCH_HAS_EVERY" = 1 ]; then
            ltm_every=(--every "$every")
        else
            ltm_dir="$OUT/$tag.scans"
            subsample_dir "$dir" "$every" "$ltm_dir"
        fi
    fi
    if "$BENCH" "$ltm_dir" --preset "$preset" --threads 1 "${ltm_every[@]+"${ltm_every[@]}"}" \
        "${lim[@]+"${lim[@]}"}" "${ltm_ref[@]+"${ltm_ref[@]}"}" --frame-log "$OUT/$tag.ltm.csv" \
        --out "$OUT/$tag.ltm.txt" > "$OUT/$tag.ltm.log" 2>&1; then
        ltm_fps="$(awk '/^speed by CPU time/ {print $(NF-5); exit}' "$OUT/$tag.ltm.log")"
        ltm_track="$(awk '/^frames:/ {
            line = $0; sub(/^frames: [0-9]+;/, "", line); sub(/ keyframes.*/, "", line)
            n = split(line, parts, ";"); ok = 0; lost = 0; other = 0
            for (i = 1; i <= n; ++i) {
                if (parts[i] !~ /[0-9]/) continue
                m = split(parts[i], w, " "); v = w[m]; st = parts[i]; sub(/ [0-9]+$/, "", st)
                gsub(/^ +/, "", st)
                if (st == "initialised" || st == "tracked" || st == "recovered") ok += v
                else if (st == "lost") lost += v
                else other += v
            }
            printf "%d/%d", ok, lost; if (other) printf "+%d", other; exit }' "$OUT/$tag.ltm.log")"
        # ltm's own tracking summary, when its benchmark prints one: registered/not, longest lost.
        if grep -q '^tracking: ' "$OUT/$tag.ltm.log"; then
            ltm_track="$(awk '/^tracking: / {printf "%d/%d", $2, $4 - $2; exit}' "$OUT/$tag.ltm.log")"
            ltm_longest="$(sed -n 's/^tracking: .* the longest \([0-9.]*\) s .*/\1/p' "$OUT/$tag.ltm.log" | head -1)"
        fi
        ltm_ate="$(ate "$OUT/$tag.ltm.txt" "$frame" "$calib" "$sub")"
        ltm_path="$(path_pct "$OUT/$tag.ltm.txt" "$sub")"
        ltm_deg="$(awk '/^observability: / {print $2; exit}' "$OUT/$tag.ltm.log")"
        ltm_off="$(awk '/^self-check: / {print $2; exit}' "$OUT/$tag.ltm.log")"
        ltm_3sig="$(sed -n 's/^self-check: .*: [0-9]* of [0-9]* (\([0-9.]*\) %)$/\1/p' "$OUT/$tag.ltm.log" | head -1)"
        [ -d "$OUT/$tag.scans" ] && rm -rf "$OUT/$tag.scans"
    else
        say "$name: ltm failed: $(tail -1 "$OUT/$tag.ltm.log")"
    fi
    ROWS+=("$name|$kept|$ltm_ate|$kiss_ate|$ltm_path|$kiss_path|${ltm_deg:--}|${ltm_off:--}|${ltm_3sig:--}|$ltm_track|${ltm_longest:--}|$ltm_fps|$kiss_fps")
done

{
    f='%-27s %6s %9s %9s %8s %8s %7s %7s %6s %13s %9s %8s %8s\n'
    printf "$f" case scans "ltm ATE" "KISS ATE" "ltm path" "KISS pth" "ltm deg" "ltm off" \
        "3sig" "ltm trk/lost" "ltm lost" "ltm fps" "KISS fps"
    for r in "${ROWS[@]+"${ROWS[@]}"}"; do
        IFS='|' read -r a b c d e g h i j k l m n <<< "$r"
        printf "$f" "$a" "$b" "$c" "$d" "$e" "$g" "$h" "$i" "$j" "$k" "$l" "$m" "$n"
    done
} | tee "$OUT/table.txt"
printf '(ATE: aligned RMSE [m] by ltm_eval traj; path: length over the reference'"'"'s [%%]; fps: CPU time, one thread; logs and poses: %s)\n' "$OUT"
