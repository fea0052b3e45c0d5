#!/usr/bin/env bash
# ./ltm bench base_journal --scenario S [--frames A:B] [--commit-every S] [--config multi|single] [--out D]
# The base station's downlink journal and its cost over one session (issue 28, item 4): the base
# station (base_station_multi.yaml on the site D/site, or base_station.yaml with --config single)
# and a robot (robot.yaml, the simulator as its sensor at the sensor's rate, namespace /robot1)
# as two hosts on the loopback interface. With --commit-every S (multi only) a version is
# committed every S seconds (`./ltm map commit`): the downlink forgets what a committed version
# holds. Every second the journal's size (du of D/base/downlink) is sampled; at the end the base
# station's CPU share and peak memory (/usr/bin/time -v) and the journal's size are printed.
# LTM_BENCH_DOMAIN: the DDS domain (default 67).
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
SCENARIO="" FRAMES="" EVERY=0 CONFIG=multi OUT="results/base-journal-$(date +%Y%m%d-%H%M%S)"
fail() { echo "ltm bench base_journal: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --scenario|--frames|--commit-every|--config|--out)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --scenario) SCENARIO="$2" ;; --frames) FRAMES="$2" ;; --commit-every) EVERY="$2" ;;
                --config) CONFIG="$2" ;; --out) OUT="$2" ;;
            esac
            shift 2 ;;
        -h|--help)
            echo "usage: ./ltm bench base_journal --scenario S [--frames A:B] [--commit-every S] [--config multi|single] [--out D]"
            exit 0 ;;
        *) fail "unknown argument '$1' (--scenario S [--frames A:B] [--commit-every S] [--config multi|single] [--out D])" ;;
    esac
done
[ -f "$SCENARIO" ] || fail "--scenario: no file '$SCENARIO'"
[[ "$EVERY" =~ ^[0-9]+$ ]] || fail "--commit-every: expected seconds (0: never), got '$EVERY'"
case "$CONFIG" in
    multi) BASE_CONFIG="$ROOT/launch_configs/base_station_multi.yaml" ;;
    single) BASE_CONFIG="$ROOT/launch_configs/base_station.yaml"
            [ "$EVERY" = 0 ] || fail "--commit-every needs --config multi (a site)" ;;
    *) fail "--config: multi or single, got '$CONFIG'" ;;
esac
start=0 count=0
if [ -n "$FRAMES" ]; then
    [[ "$FRAMES" =~ ^([0-9]+):([0-9]+)$ ]] || fail "--frames: expected A:B, got '$FRAMES'"
    start=${BASH_REMATCH[1]}; count=$((BASH_REMATCH[2] - BASH_REMATCH[1]))
    [ "$count" -gt 0 ] || fail "--frames: B must be above A"
fi
for exe in ltm_host; do
    [ -x "$BIN/$exe" ] || fail "$BIN/$exe is not built (./ltm setup, or ninja -C build)"
done
[ -x /usr/bin/time ] || fail "/usr/bin/time is missing (Debian package 'time')"
SCENARIO="$(cd "$(dirname "$SCENARIO")" && pwd)/$(basename "$SCENARIO")"
rm -rf "$OUT"; mkdir -p "$OUT/base" || fail "--out: cannot create $OUT"
OUT="$(cd "$OUT" && pwd)"
DOMAIN="${LTM_BENCH_DOMAIN:-67}"
DDS=(--set "domain_id=$DOMAIN" --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}')
case "$(awk '/^ *model:/ {print $2; exit}' "$SCENARIO")" in  # the sensor's preset
    hdl64e) preset=hdl64 ;; vlp32c) preset=vlp32 ;; vlp16) preset=vlp16 ;; *) preset=narrow ;;
esac
awk -v scenario="$SCENARIO" -v start="$start" -v count="$count" '
    /^  - name: player$/ { skip = 1
        print "  - name: player\n    type: simulator\n    params:\n      scenario: " scenario \
              "\n      mode: realtime\n      start: " start "\n      count: " count \
              "\n      wait_for_readers: 3"; next }
    /^  - name:/ { skip = 0 }
    skip { next } { print }' "$ROOT/launch_configs/robot.yaml" > "$OUT/robot.yaml"
NS=(--set namespace=/robot1)
[ "$CONFIG" = single ] && NS=(--set namespace=/robot)
echo "ltm bench base_journal: $(basename "$SCENARIO") ${FRAMES:+frames $FRAMES }through $(basename "$BASE_CONFIG"), commit every ${EVERY} s (0: never), domain $DOMAIN; results in $OUT"
PIDS=()
trap 'for p in "${PIDS[@]}"; do kill -INT "$p" 2>/dev/null; done; wait' EXIT
env LTM_ROOT="$ROOT" LTM_SITE="$OUT/site" LTM_OUT="$OUT/base" /usr/bin/time -v -o "$OUT/base_time.txt" \
    "$BIN/ltm_host" "$BASE_CONFIG" "${DDS[@]}" --set mapping.preset=$preset --set idle_exit_s=8 \
    > "$OUT/base.log" 2>&1 &
BASE_PID=$!; PIDS+=("$BASE_PID")
env LTM_ROOT="$ROOT" LTM_SITE="$OUT/robot_site" LTM_OUT="$OUT/robot" \
    "$BIN/ltm_host" "$OUT/robot.yaml" "${DDS[@]}" "${NS[@]}" \
    --set odometry.preset=$preset --set keyframe_digest.preset=$preset \
    --set localisation.preset=$preset > "$OUT/robot.log" 2>&1 &
ROBOT_PID=$!; PIDS+=("$ROBOT_PID")
t0=$SECONDS next=$EVERY peak=0
echo "s journal_KiB" > "$OUT/journal.txt"
while kill -0 "$BASE_PID" 2>/dev/null; do
    t=$((SECONDS - t0))
    kib=$(du -sk "$OUT/base/downlink" 2>/dev/null | cut -f1); kib=${kib:-0}
    echo "$t $kib" >> "$OUT/journal.txt"
    [ "$kib" -gt "$peak" ] && peak=$kib
    [ $((t % 30)) = 0 ] && echo "  ${t} s: journal ${kib} KiB"
    if [ "$EVERY" -gt 0 ] && [ "$t" -ge "$next" ] && kill -0 "$ROBOT_PID" 2>/dev/null; then
        next=$((t + EVERY))
        "$BIN/ltm_host" "$ROOT/launch_configs/tools/map_request.yaml" "${DDS[@]}" \
            --set map_request.command=commit --set 'namespace=""' >> "$OUT/commits.log" 2>&1 &
    fi
    sleep 1
done
wait "$ROBOT_PID"; robot_rc=$?
wait "$BASE_PID"; base_rc=$?
PIDS=()
trap - EXIT
[ "$robot_rc" = 0 ] && [ "$base_rc" = 0 ] || fail "robot exit $robot_rc, base station exit $base_rc (logs in $OUT)"
final=$(du -sk "$OUT/base/downlink" | cut -f1)
wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$OUT/base_time.txt")
user=$(sed -n 's/.*User time (seconds): //p' "$OUT/base_time.txt")
sys=$(sed -n 's/.*System time (seconds): //p' "$OUT/base_time.txt")
rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$OUT/base_time.txt")
secs=$(echo "$wall" | awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; print s }')
scans=$(sed -n 's/.*\[odometry\] \([0-9]*\) scans,.*/\1/p' "$OUT/robot.log" | tail -n 1)
commits=$(grep -c "committed v" "$OUT/commits.log" 2>/dev/null)
echo "base station ($(basename "$BASE_CONFIG")): ${scans:-?} scans, wall ${secs} s, CPU ${user} s user + ${sys} s system = $(awk -v u="$user" -v s="$sys" -v w="$secs" 'BEGIN { printf "%.1f %% of one core", 100 * (u + s) / w }'), peak memory $((rss / 1024)) MiB"
echo "journal: peak ${peak} KiB, at the end ${final} KiB; ${commits:-0} versions committed on request"
grep -h "KiB of journal released\|not replayed" "$OUT/base.log" | tail -n 3 | sed 's/^/  /'
