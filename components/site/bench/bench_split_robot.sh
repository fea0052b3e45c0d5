#!/usr/bin/env bash
# ./ltm bench split_robot --scenario S --days N [--out D]
# The split robot (issue 26) day by day: each day the base station (base_station_multi.yaml, its
# site D/site) and the robot (robot.yaml with the simulator as its sensor, namespace /robot1, its
# own site D/robot_site) run as two hosts on the loopback interface; the robot localises and
# maintains on its site, the base station maps and commits the day's version, which the robot
# receives the next day. Scored by `ltm_eval lifelong` exactly as `./ltm bench lifelong` scores
# the composed robot_lifelong.yaml (map poses in one alignment fitted on day 0's final SLAM
# keyframes, changed objects in the map after each day, ...), and the uplink's bytes by topic
# (maintenance's map_changes among them) from the uplink's own log.
# LTM_BENCH_DOMAIN: the DDS domain (default 66).
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
SCENARIO="" DAYS="" OUT="results/split-robot-$(date +%Y%m%d-%H%M%S)"
fail() { echo "ltm bench split_robot: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --scenario|--days|--out)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in --scenario) SCENARIO="$2" ;; --days) DAYS="$2" ;; --out) OUT="$2" ;; esac
            shift 2 ;;
        -h|--help)
            echo "usage: ./ltm bench split_robot --scenario S --days N [--out D]"; exit 0 ;;
        *) fail "unknown argument '$1' (--scenario S --days N [--out D])" ;;
    esac
done
[ -f "$SCENARIO" ] || fail "--scenario: no file '$SCENARIO'"
[[ "$DAYS" =~ ^[1-9][0-9]*$ ]] || fail "--days: expected a count >= 1, got '$DAYS'"
for exe in ltm_host ltm_sim ltm_eval; do
    [ -x "$BIN/$exe" ] || fail "$BIN/$exe is not built (./ltm setup, or ninja -C build)"
done
SCENARIO="$(cd "$(dirname "$SCENARIO")" && pwd)/$(basename "$SCENARIO")"
mkdir -p "$OUT" || fail "--out: cannot create $OUT"
OUT="$(cd "$OUT" && pwd)"
DOMAIN="${LTM_BENCH_DOMAIN:-66}"
DDS=(--set "domain_id=$DOMAIN" --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}')
case "$(awk '/^ *model:/ {print $2; exit}' "$SCENARIO")" in  # the sensor's preset
    hdl64e) preset=hdl64 ;; vlp32c) preset=vlp32 ;; vlp16) preset=vlp16 ;; *) preset=narrow ;;
esac

# robot.yaml with the simulator in place of its kitti_player, and the trajectories written.
awk -v scenario="$SCENARIO" '
    /^  - name: player$/ { skip = 1
        print "  - name: player\n    type: simulator\n    params:\n      scenario: " scenario \
              "\n      mode: realtime\n      wait_for_readers: 3"; next }
    /^  - name:/ { skip = 0 }
    skip { next } { print }' "$ROOT/launch_configs/robot.yaml" > "$OUT/robot.yaml"
cat >> "$OUT/robot.yaml" <<'EOF'
  - name: localised
    type: trajectory_writer
    params:
      tum_file: ${LTM_OUT}/localisation_tum.txt
      input: pose_with_covariance
  - name: truth
    type: trajectory_writer
    params:
      tum_file: ${LTM_OUT}/ground_truth_tum.txt
      input: pose
    remap: {pose: ground_truth}
EOF

echo "ltm bench split_robot: $DAYS days of $(basename "$SCENARIO") (preset $preset, domain $DOMAIN), results in $OUT"
BASE_PID=""
trap '[ -n "$BASE_PID" ] && kill -INT "$BASE_PID" 2>/dev/null; wait' EXIT
for ((d = 0; d < DAYS; d++)); do
    dir="$OUT/day$d"
    rm -rf "$dir"; mkdir -p "$dir/base"
    "$BIN/ltm_sim" "$SCENARIO" --session "$d" --truth-only --quiet --out "$dir/truth" ||
        fail "day $d: ltm_sim --truth-only failed"
    start=$SECONDS
    env LTM_ROOT="$ROOT" LTM_SITE="$OUT/site" LTM_OUT="$dir/base" "$BIN/ltm_host" \
        "$ROOT/launch_configs/base_station_multi.yaml" "${DDS[@]}" --set mapping.preset=$preset \
        --set idle_exit_s=6 > "$dir/base.log" 2>&1 &
    BASE_PID=$!
    env LTM_ROOT="$ROOT" LTM_SITE="$OUT/robot_site" LTM_OUT="$dir" /usr/bin/time -v -o "$dir/time.txt" \
        "$BIN/ltm_host" "$OUT/robot.yaml" "${DDS[@]}" --set namespace=/robot1 \
        --set odometry.preset=$preset --set keyframe_digest.preset=$preset \
        --set localisation.preset=$preset --set player.session=$d > "$dir/host.log" 2>&1
    robot_rc=$?
    wait "$BASE_PID"; base_rc=$?; BASE_PID=""
    echo "$robot_rc" > "$dir/exit_status"
    echo "  day $d: robot exit $robot_rc, base station exit $base_rc after $((SECONDS - start)) s; logs $dir/host.log, $dir/base.log"
    [ "$robot_rc" = 0 ] && [ "$base_rc" = 0 ] || fail "day $d failed"
    # The layout ltm_eval lifelong reads (as ./ltm bench lifelong makes it).
    ln -sfn localisation_tum.txt "$dir/map_poses_tum.txt"
    [ "$d" = 0 ] && ln -sfn base/slam_robot1_tum.txt "$dir/slam_tum.txt"
    newest=$(ls -d "$OUT/site/versions/v"* 2>/dev/null | sort | tail -n 1)
    [ -n "$newest" ] || fail "day $d: no version in $OUT/site/versions"
    cp -r "$newest/map" "$dir/next_map" || fail "day $d: cannot copy $newest/map"
    cp "$OUT/robot_site/robot/maintenance/long_term_map.bin" "$dir/maintained" 2>/dev/null
    echo "$newest" > "$dir/version"
    # What crossed the uplink: the uplink's final line, and the base station's applied changes.
    grep -h "\[uplink\] final:" "$dir/host.log" | sed 's/^/    /'
    grep -h "\[localisation\] site .* arrived\|\[maintenance\] pass" "$dir/host.log" | sed 's/^/    /'
    grep -h "voxels cleared from the local maps" "$dir/base.log" | sed 's/^/    /'
done
trap - EXIT
"$BIN/ltm_eval" lifelong --run "$OUT" --days "$DAYS" --out "$OUT/score"
