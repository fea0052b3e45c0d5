#!/usr/bin/env bash
# A robot restarted in the middle of a mission (issue 15), on the loopback interface (no root):
# tiny_loop's first half is driven while no base station listens (everything waits in the robot's
# backlog) and the robot stops; the base station starts; the robot starts again from its start
# point and drives the whole loop. The second run must send the first run's backlog, then its own;
# the base station must get every message once, and the mapping must take the second run as a new
# odometry segment of the same robot (numbers continued, nothing refused) that a loop joins to the
# map. (tiny_loop has 41 scans and the replay repeats the first run's stamps: the mapping searches
# every keyframe, recent or not.)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
for exe in ltm_host ltm_sim; do
    [ -x "$BIN/$exe" ] || { echo "SKIPPED: $BIN/$exe is not built"; exit 77; }
done
T="$(mktemp -d /tmp/ltm_robot_restart.XXXXXX)"
BASE_PID=""
cleanup() {
    [ -n "$BASE_PID" ] && kill -INT "$BASE_PID" 2>/dev/null && wait "$BASE_PID" 2>/dev/null
    rm -rf "$T"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; for f in "$T"/*.log; do echo "--- $f"; tail -n 25 "$f"; done; exit 1; }

"$BIN/ltm_sim" --quiet --out "$T/data" "$ROOT/components/simulator/scenarios/tiny_loop.yaml" \
    > "$T/sim.log" 2>&1 || fail "the simulator failed"
scans=$(wc -l < "$T/data/times.txt")
case "$(awk '/^ *model:/ {print $2; exit}' "$T/data/scenario.yaml")" in  # the sensor's presets
    hdl64e) preset=hdl64 ;; vlp32c) preset=vlp32 ;; vlp16) preset=vlp16 ;; *) preset=narrow ;;
esac
half=$((scans / 2))
DDS=(--set domain_id=217 --set 'dds.interfaces=[lo]' --set dds.multicast=false
     --set 'dds.peers=[127.0.0.1]')
robot() {  # robot LOG START COUNT [SETS...]
    local log="$1" start="$2" count="$3"; shift 3
    env LTM_ROOT="$ROOT" LTM_DATA="$T/data" LTM_OUT="$T/robot" LTM_SITE="$T/robot_site" \
        "$BIN/ltm_host" "$ROOT/launch_configs/robot.yaml" "${DDS[@]}" \
        --set odometry.preset=$preset --set keyframe_digest.preset=$preset \
        --set player.start="$start" --set player.count="$count" "$@" > "$T/$log" 2>&1
}
stored() { sed -n 's/.*\[uplink\] final: \([0-9]*\) messages.*/\1/p' "$T/$1" | tail -n 1; }

# Run 1: nobody listens; the robot stops after the first half with everything in its backlog.
robot run1.log 0 "$half" --set uplink.drain_s=0 || fail "the first run failed"
n1=$(stored run1.log)
[ -n "$n1" ] && [ "$n1" -gt 0 ] || fail "the first run stored nothing"
grep -q "the unacknowledged packets stay in" "$T/run1.log" || fail "run 1 left no backlog"

# The base station, then run 2 from where run 1 stopped.
env LTM_ROOT="$ROOT" LTM_OUT="$T/base" "$BIN/ltm_host" "$ROOT/launch_configs/base_station.yaml" \
    "${DDS[@]}" --set mapping.preset=$preset --set idle_exit_s=0 --set shutdown_timeout_s=60 \
    --set mapping.loop_detection.exclude_recent_keyframes=0 \
    --set mapping.loop_detection.exclude_recent_seconds=0 \
    > "$T/base.log" 2>&1 &
BASE_PID=$!
sleep 1
robot run2.log 0 0 || fail "the second run failed"
n2=$(stored run2.log)
kill -INT "$BASE_PID"; wait "$BASE_PID"; rc=$?; BASE_PID=""
[ "$rc" = 0 ] || fail "the base station exited with $rc"

grep -Eq "earlier run [0-9a-f]+ left $n1 unacknowledged packets" "$T/run2.log" \
    || fail "run 2 did not take up run 1's $n1 packets"
grep -q "the backlog of earlier run [0-9a-f]* is delivered" "$T/run2.log" \
    || fail "run 1's backlog was not delivered"
grep -q "numbered on from" "$T/run2.log" || fail "run 2 did not number on"
line=$(grep "\[downlink\] final:" "$T/base.log" | tail -n 1)
echo "$line" | grep -Eq "$((n1 + n2)) messages delivered" \
    || fail "expected $n1 + $n2 messages delivered: $line"
grep -q " 0 lost" <<< "$line" || fail "lost packets: $line"
if grep -q "not added" "$T/base.log"; then fail "the mapping refused messages"; fi
grep -Eq "\[mapping\] segment 1 .*joined to the map by a loop" "$T/base.log" \
    || fail "the second run was not joined to the map as segment 1"
echo "ok: run 1 stored $n1 messages, run 2 $n2; all delivered once; run 2 joined as segment 1"
