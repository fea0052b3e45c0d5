#!/usr/bin/env bash
# ./ltm bench link [--loss PCT] [--loss-on in|out|both] [--rate MBIT] [--outage S@T ...]
#                  [--linger S] [--drain S] [--scenario FILE] [--frames A:B] [--out DIR] [--require TOPIC ...]
#                  [--restart-base T] [--compare] [--require-same-map]
# The robot and the base station over a link you can break: two network namespaces (robot, base)
# joined by a veth pair, nftables `numgen random` drops on the base station's side for loss (this
# kernel has no netem), `tc tbf` on both ends for the rate, a drop-all rule for each outage. The
# scenario is simulated to a KITTI folder, launch_configs/robot.yaml runs in the robot namespace
# and base_station.yaml in the base namespace, each with a recorder of the topics that cross the
# link added to its process; the report compares the two recordings message by message (CRC).
# Keyframes and local maps cross through the robot's uplink and the base station's downlink
# (components/link: journaled on both sides, acknowledged, resent): the robot's recording holds
# what its odometry published (onboard/...), the base station's what its downlink handed on.
# --restart-base T kills the base station T s after the robot started (SIGKILL: a crash) and
# starts it again; the last base station's recording must then hold every message exactly once.
# --compare also runs the same scans through one process (player, odometry, mapping: the
# composed run) and compares its saved map with the base station's (ltm_map_diff).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
BIN="$BUILD/bin"
LOSS=0; LOSS_ON=both; RATE=0; SCENARIO="$ROOT/components/simulator/scenarios/tiny_loop.yaml"
LINGER=""; DRAIN=3; FRAMES=""; OUT=""; OUTAGES=(); REQUIRE=(); TOPICS=(odometry keyframe local_map)
RESTART=""; COMPARE=0; SAME_MAP=0
usage() {
    echo "Robot and base station in two network namespaces over a veth link with loss, a rate"
    echo "limit and outages; per topic what was sent and delivered, the bytes on the link"
    printf 'Usage: ./ltm bench link [OPTIONS]\n\nOptions:\n'
    printf '  %-24s%s\n' "-h,--help" "Print this help message and exit" \
        "--loss PCT=0" "packets dropped at random [%] (0..100, two decimals)" \
        "--loss-on in|out|both" "where on the base station: ingress, egress or both (both)" \
        "--rate MBIT=0" "tc tbf rate of each direction [Mbit/s] (0: unlimited)" \
        "--outage S@T" "drop everything for S s from T s after the robot starts (repeatable)" \
        "--linger S" "the robot's writers wait S s for acknowledgements at exit (Cyclone's 1 s)" \
        "--drain S=$DRAIN" "the base station keeps listening S s after the robot exited" \
        "--scenario FILE" "simulator scenario (default tiny_loop)" \
        "--frames A:B" "scans A..B-1 of the scenario's session 0 (default all)" \
        "--out DIR" "keep the run here (default: a temporary folder, removed)" \
        "--require TOPIC" "exit 1 unless every message of TOPIC arrived (repeatable)" \
        "--restart-base T" "kill the base station T s after the robot started, start it again" \
        "--compare" "also run the scans in one process; compare its map with the base station's" \
        "--require-same-map" "with --compare: exit 1 unless anchors agree to 1 mm, same loops"
}
fail() { echo "ltm bench link: $*" >&2; exit 2; }   # a wrong command line
die() { echo "ltm bench link: $*" >&2; exit 1; }    # the machine cannot do it
number='^[0-9]+([.][0-9]+)?$'
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --compare) COMPARE=1; shift; continue ;;
        --require-same-map) COMPARE=1; SAME_MAP=1; shift; continue ;;
        --loss|--loss-on|--rate|--outage|--linger|--drain|--scenario|--frames|--out|--require|--restart-base)
            if [ $# -lt 2 ] || [ "${2:0:2}" = "--" ]; then fail "$1: needs a value"; fi
            case "$1" in
                --loss) if ! [[ "$2" =~ $number ]] || ! awk -v v="$2" 'BEGIN {exit !(v <= 100)}'; then
                            fail "--loss: expected a percentage 0..100, got '$2'"
                        fi
                        LOSS="$2" ;;
                --loss-on) case "$2" in in|out|both) LOSS_ON="$2" ;;
                               *) fail "--loss-on: expected in, out or both, got '$2'" ;; esac ;;
                --rate) [[ "$2" =~ $number ]] || fail "--rate: expected Mbit/s, got '$2'"
                        RATE="$2" ;;
                --outage) [[ "$2" =~ ^[0-9]+([.][0-9]+)?@[0-9]+([.][0-9]+)?$ ]] \
                              || fail "--outage: expected SECONDS@START (30@20), got '$2'"
                          OUTAGES+=("$2") ;;
                --drain) [[ "$2" =~ $number ]] || fail "--drain: expected seconds, got '$2'"
                         DRAIN="$2" ;;
                --linger) [[ "$2" =~ $number ]] || fail "--linger: expected seconds, got '$2'"
                          LINGER="$2" ;;
                --scenario) [ -f "$2" ] || fail "--scenario: no such file: $2"
                            SCENARIO="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")" ;;
                --frames) [[ "$2" =~ ^[0-9]*:[0-9]*$ ]] || fail "--frames: expected A:B, got '$2'"
                          FRAMES="$2" ;;
                --out) OUT="$2" ;;
                --restart-base) [[ "$2" =~ $number ]] || fail "--restart-base: expected seconds, got '$2'"
                                RESTART="$2" ;;
                --require) case " ${TOPICS[*]} " in *" $2 "*) REQUIRE+=("$2") ;;
                               *) fail "--require: expected one of ${TOPICS[*]}, got '$2'" ;; esac ;;
            esac
            shift 2 ;;
        -*) fail "$1: unknown option" ;;
        *) fail "$1: unexpected argument" ;;
    esac
done

[ "$(id -u)" -eq 0 ] || die "needs root (network namespaces, nftables, tc): run it as root"
command -v ip >/dev/null || die "ip (iproute2) is not installed: run ./ltm setup"
command -v tc >/dev/null || die "tc (iproute2) is not installed: run ./ltm setup"
command -v nft >/dev/null || die "nft (nftables) is not installed: run ./ltm setup"
for exe in ltm_host ltm_sim ltm_mcap ltm_map_diff; do
    [ -x "$BIN/$exe" ] || die "$exe is not built in $BUILD: run ./ltm setup"
done

# Names unique to this run, so that two runs (or a stale one) do not meet.
TAG="$$"
NS_ROBOT="ltm_robot_$TAG"; NS_BASE="ltm_base_$TAG"
DEV_ROBOT="ltmr$TAG"; DEV_BASE="ltmb$TAG"
ADDR_ROBOT=10.77.0.1; ADDR_BASE=10.77.0.2
WORK="$(mktemp -d)"
PIDS=()
cleanup() {
    local pid
    for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
    for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
    ip netns del "$NS_ROBOT" 2>/dev/null || true
    ip netns del "$NS_BASE" 2>/dev/null || true
    ip link del "$DEV_ROBOT" 2>/dev/null || true   # still here when the move failed
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

ip netns add "$NS_ROBOT" 2>/dev/null || die "cannot create a network namespace (ip netns add failed): not available here"
ip netns add "$NS_BASE" || die "cannot create a second network namespace"
ip link add "$DEV_ROBOT" type veth peer name "$DEV_BASE" || die "cannot create a veth pair"
ip link set "$DEV_ROBOT" netns "$NS_ROBOT"
ip link set "$DEV_BASE" netns "$NS_BASE"
ip -n "$NS_ROBOT" addr add "$ADDR_ROBOT/24" dev "$DEV_ROBOT"
ip -n "$NS_BASE" addr add "$ADDR_BASE/24" dev "$DEV_BASE"
for ns in "$NS_ROBOT" "$NS_BASE"; do ip -n "$ns" link set lo up; done
ip -n "$NS_ROBOT" link set "$DEV_ROBOT" up
ip -n "$NS_BASE" link set "$DEV_BASE" up

# Loss: numgen random drops of Ethernet frames (IP fragments one by one, as a radio loses them) on
# the base station's end of the veth: netdev ingress (robot -> base) and egress (base -> robot).
loss_rules=""
if awk -v v="$LOSS" 'BEGIN {exit !(v > 0)}'; then
    n=$(awk -v v="$LOSS" 'BEGIN {printf "%d", v * 100 + 0.5}')
    [ "$LOSS_ON" = out ] || loss_rules+="add rule netdev ltm_link in numgen random mod 10000 < $n counter drop
"
    [ "$LOSS_ON" = in ] || loss_rules+="add rule netdev ltm_link out numgen random mod 10000 < $n counter drop
"
fi
# The outage chains come first (priority -10): an outage adds a drop-all rule to both.
ip netns exec "$NS_BASE" nft -f - <<NFT || die "nft could not load the link rules (no nf_tables netdev hooks in this kernel?)"
add table netdev ltm_link
add chain netdev ltm_link outage_in { type filter hook ingress device "$DEV_BASE" priority -10; policy accept; }
add chain netdev ltm_link outage_out { type filter hook egress device "$DEV_BASE" priority -10; policy accept; }
add chain netdev ltm_link in { type filter hook ingress device "$DEV_BASE" priority 0; policy accept; }
add chain netdev ltm_link out { type filter hook egress device "$DEV_BASE" priority 0; policy accept; }
$loss_rules
NFT
if awk -v v="$RATE" 'BEGIN {exit !(v > 0)}'; then
    # tbf: a burst of 10 ms at the rate (at least 16 KiB), 100 ms of queue.
    burst=$(awk -v r="$RATE" 'BEGIN {b = r * 1e6 / 8 / 100; if (b < 16384) b = 16384; printf "%d", b}')
    ip netns exec "$NS_ROBOT" tc qdisc add dev "$DEV_ROBOT" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms \
        || die "tc tbf is not available"
    ip netns exec "$NS_BASE" tc qdisc add dev "$DEV_BASE" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms
fi

# The scenario as a KITTI folder; the odometry and mapping presets follow its sensor.
DATA="$WORK/data"
sim_args=(--quiet --out "$DATA")
[ -n "$FRAMES" ] && sim_args+=(--frames "$FRAMES")
"$BIN/ltm_sim" "${sim_args[@]}" "$SCENARIO" >/dev/null || die "the simulator failed on $SCENARIO"
model=$(awk '/^ *model:/ {print $2; exit}' "$DATA/scenario.yaml")
case "$model" in
    hdl64e) preset=hdl64 ;; vlp32c) preset=vlp32 ;; vlp16) preset=vlp16 ;; *) preset=narrow ;;
esac
scans=$(wc -l < "$DATA/times.txt")

RUN="${OUT:-$WORK/run}"
mkdir -p "$RUN"
RUN="$(cd "$RUN" && pwd)"
rm -rf "$RUN/robot" "$RUN/base" "$RUN/composed"
rm -f "$RUN"/base*.log "$RUN/robot.log" "$RUN/composed.log"
# Each launch config with a recorder in its own process (what the robot's odometry published; what
# the base station's mapping was given), so the recording adds no traffic.
with_recorder() {
    cat "$1"
    printf '  - name: link_recorder\n    type: recorder\n    params: {file: "%s", topics: %s, compression: none}\n' \
        "$2" "$3"
}
with_recorder "$ROOT/launch_configs/robot.yaml" "$RUN/robot/sent.mcap" \
    "[odometry, onboard/keyframe, onboard/local_map]" > "$WORK/robot.yaml"
with_recorder "$ROOT/launch_configs/base_station.yaml" '${LTM_RECORDING}' \
    "[odometry, keyframe, local_map]" > "$WORK/base.yaml"
dds() { echo "dds={interfaces: [$1], multicast: false, peers: [$2]${3:+, extra_xml: \"$3\"}}"; }
robot_xml=""
[ -n "$LINGER" ] && robot_xml="<Internal><WriterLingerDuration>${LINGER} s</WriterLingerDuration></Internal>"

rate_text="$RATE Mbit/s"; [ "$rate_text" = "0 Mbit/s" ] && rate_text=unlimited
echo "== link: loss $LOSS % ($LOSS_ON), rate $rate_text, outages: ${OUTAGES[*]:-none}"
echo "   scenario $(basename "$SCENARIO") ${FRAMES:+frames $FRAMES }($scans scans, $model), run in $RUN"
start_base() {  # start_base N: the Nth start of the base station (its own recording and log)
    local suffix=""; [ "$1" -gt 1 ] && suffix="$1"
    BASE_RECORDING="$RUN/base/delivered$suffix.mcap"
    ip netns exec "$NS_BASE" env LTM_ROOT="$ROOT" LTM_OUT="$RUN/base" LTM_RECORDING="$BASE_RECORDING" \
        "$BIN/ltm_host" "$WORK/base.yaml" --set "$(dds "$DEV_BASE" "$ADDR_ROBOT")" \
        --set "mapping.preset=$preset" --set idle_exit_s=0 --set shutdown_timeout_s=60 \
        >> "$RUN/base$suffix.log" 2>&1 &
    base_pid=$!; PIDS+=("$base_pid")
}
start_base 1
sleep 1
start=$(date +%s.%N)
ip netns exec "$NS_ROBOT" env LTM_ROOT="$ROOT" LTM_DATA="$DATA" LTM_OUT="$RUN/robot" \
    "$BIN/ltm_host" "$WORK/robot.yaml" --set "$(dds "$DEV_ROBOT" "$ADDR_BASE" "$robot_xml")" \
    --set "odometry.preset=$preset" > "$RUN/robot.log" 2>&1 &
robot_pid=$!; PIDS+=("$robot_pid")
for o in "${OUTAGES[@]}"; do
    (
        s="${o%@*}"; t="${o#*@}"
        sleep "$t"
        ip netns exec "$NS_BASE" nft -f - <<NFT
add rule netdev ltm_link outage_in counter drop
add rule netdev ltm_link outage_out counter drop
NFT
        sleep "$s"
        ip netns exec "$NS_BASE" nft flush chain netdev ltm_link outage_in
        ip netns exec "$NS_BASE" nft flush chain netdev ltm_link outage_out
        date +%H:%M:%S.%N > "$WORK/outage_end_$t"
    ) &
    PIDS+=("$!")
done
if [ -n "$RESTART" ]; then
    sleep "$RESTART"
    if kill -0 "$robot_pid" 2>/dev/null; then
        echo "   base station killed (SIGKILL) $RESTART s after the robot started; started again"
        kill -KILL "$base_pid" 2>/dev/null || true
        wait "$base_pid" 2>/dev/null || true
        start_base 2
    else
        echo "   --restart-base $RESTART: the robot had finished already; no restart"
    fi
fi
robot_rc=0; wait "$robot_pid" || robot_rc=$?
robot_end=$(date +%s.%N)
# The base station runs until the robot is gone and DRAIN s more (not an idle timer: a discovery
# slowed by loss would stop it before the first message), then stops cleanly (maps saved).
sleep "$DRAIN"
kill -TERM "$base_pid" 2>/dev/null || true
base_rc=0; wait "$base_pid" || base_rc=$?
[ "$robot_rc" -eq 0 ] || { echo "   robot exited with $robot_rc:"; tail -n 3 "$RUN/robot.log"; }
[ "$base_rc" -eq 0 ] || { echo "   base station exited with $base_rc:"; tail -n 3 "$RUN/base.log"; }
if [ "$robot_rc" -ne 0 ] || [ "$base_rc" -ne 0 ]; then die "a side of the link failed (its last lines above)"; fi
awk -v a="$start" -v b="$robot_end" 'BEGIN {printf "   robot ran %.1f s\n", b - a}'

# Bytes on the link: the veth counters of the robot's end (TX: robot -> base, RX: base -> robot).
link_stats() {  # rx_bytes rx_packets tx_bytes tx_packets
    ip -n "$NS_ROBOT" -s link show dev "$DEV_ROBOT" |
        awk '/RX:/ {getline; rb=$1; rp=$2} /TX:/ {getline; tb=$1; tp=$2} END {print rb, rp, tb, tp}'
}
read -r rx_bytes rx_packets tx_bytes tx_packets < <(link_stats)
echo "== link bytes (veth, robot end)"
awk -v tb="$tx_bytes" -v tp="$tx_packets" -v rb="$rx_bytes" -v rp="$rx_packets" -v a="$start" -v b="$robot_end" \
    'BEGIN {d = b - a; printf "   robot -> base: %d bytes in %d packets (%.2f Mbit/s over the robot'"'"'s %.1f s)\n", tb, tp, tb * 8 / d / 1e6, d
            printf "   base -> robot: %d bytes in %d packets\n", rb, rp}'
# Bytes per km: the path of the simulated ground truth (KITTI poses: x, y, z in columns 4, 8, 12).
km=$(awk 'NR > 1 {d += sqrt(($4 - x) ^ 2 + ($8 - y) ^ 2 + ($12 - z) ^ 2)} {x = $4; y = $8; z = $12}
          END {printf "%.4f", d / 1000}' "$DATA/poses.txt")
awk -v tb="$tx_bytes" -v km="$km" 'BEGIN {if (km > 0) printf "   robot -> base per km driven (%.0f m): %.1f MB\n", km * 1000, tb / 1e6 / km}'
# Frames dropped by the loss rules of each direction (outage drops are flushed with their rule).
dropped() {
    ip netns exec "$NS_BASE" nft list chain netdev ltm_link "$1" |
        awk '/counter packets/ {for (i = 1; i < NF; i++) if ($i == "packets") n += $(i + 1)} END {print n + 0}'
}
echo "   frames dropped for loss: $(dropped in) robot -> base, $(dropped out) base -> robot"

echo "== per topic: sent by the robot, delivered to the base station (compared byte for byte)"
BASE_SIDE="${BASE_RECORDING%.mcap}"; BASE_SIDE="${BASE_SIDE#$RUN/}"
for side in robot/sent "$BASE_SIDE"; do
    [ -f "$RUN/$side.mcap" ] || die "no recording $RUN/$side.mcap (--out DIR keeps the logs)"
    "$BIN/ltm_mcap" manifest "$RUN/$side.mcap" -o "$RUN/$side.json"
done
# One manifest line a message: topic, publish time (the writer's) and the CDR bytes. A message is
# delivered when the base station recorded the same topic and bytes (the downlink publishes again,
# so its publish time is its own); a second copy in the base station's recording is a duplicate
# (applied twice). One missing before the topic's first delivered message was published before
# the base station's reader was matched (discovery). The robot's recorder finds the topics by
# discovery too and can miss a topic's first message: what only the base station recorded counts
# as sent (and is reported).
awk -v req=" ${REQUIRE[*]} " '
    function field(name,   i, r) {
        i = index($0, "\"" name "\": \""); if (!i) return ""
        r = substr($0, i + length(name) + 5); return substr(r, 1, index(r, "\"") - 1)
    }
    function topic_of(t) { if (!(t in order)) { order[t] = ++nt; name[nt] = t } }
    !/"data_hex"/ || !/"topic"/ { next }
    { t = field("topic"); sub(/^rt\/[^\/]*\//, "", t); sub(/^onboard\//, "", t)
      p = field("publish_time"); d = field("data_hex") }
    FNR == NR { key = t SUBSEP d; if (key in got) dup[t]++; got[key] = length(d) / 2
                if (!(t in first) || p < first[t]) first[t] = p; next }
    {
        n++; topic[n] = t; pub[n] = p; sent[t]++; bytes[t] += length(d) / 2; topic_of(t)
        key = t SUBSEP d
        if (key in got) { ok[t]++; seen[key] = 1 } else { miss[n] = 1 }
    }
    END {
        for (key in got) if (!(key in seen)) {
            split(key, k, SUBSEP); topic_of(k[1])
            sent[k[1]]++; ok[k[1]]++; unrec[k[1]]++; bytes[k[1]] += got[key]
        }
        bad = 0
        for (i = 1; i <= nt; i++) {
            t = name[i]; early = 0; late = 0
            for (j = 1; j <= n; j++) if (topic[j] == t && (j in miss)) {
                if (!(t in first) || pub[j] < first[t]) early++; else late++
            }
            printf "   %-10s sent %4d (%8.2f MiB)  delivered %4d  missing %d", t, sent[t], bytes[t] / 1048576, ok[t] + 0, sent[t] - ok[t]
            if (sent[t] > ok[t]) printf " (%d before the base station matched, %d after)", early, late
            if (unrec[t]) printf " [%d only in the base station'"'"'s recording]", unrec[t]
            if (dup[t]) printf " DUPLICATES %d", dup[t]
            printf "\n"
            if ((sent[t] > ok[t] || dup[t]) && index(req, " " t " ")) bad = 1
        }
        exit bad
    }' "$RUN/$BASE_SIDE.json" "$RUN/robot/sent.json" || required_missing=1
awk -v end="$robot_end" '/"log_time"/ {i = index($0, "\"log_time\": \""); t = substr($0, i + 13, 19) + 0
                               if (t > last) last = t}
    END {if (last) printf "   last message received by the base station %.1f s %s the robot exited\n", \
             (last / 1e9 > end ? last / 1e9 - end : end - last / 1e9), (last / 1e9 > end ? "after" : "before")}' \
    "$RUN/$BASE_SIDE.json"
# Each outage: how long after the link came back the uplink's backlog was delivered (its log).
sod() { awk -F: '{printf "%.3f", $1 * 3600 + $2 * 60 + $3}' <<< "$1"; }
for o in "${OUTAGES[@]}"; do
    t="${o#*@}"; [ -f "$WORK/outage_end_$t" ] || continue
    back=$(sod "$(cut -c1-12 "$WORK/outage_end_$t")")
    line=$(awk -v b="$back" '/\[uplink\] backlog delivered/ {split($1, h, ":"); s = h[1] * 3600 + h[2] * 60 + h[3]
                                                            if (s >= b) {print s - b; exit}}' "$RUN/robot.log")
    if [ -n "$line" ]; then
        printf '   outage %s: the backlog was delivered %.1f s after the link came back\n' "$o" "$line"
    else
        echo "   outage $o: no 'backlog delivered' after the link came back (robot.log)"
    fi
done
# The link components' own account (their final lines).
grep -h "uplink.*final\|downlink.*final" "$RUN/robot.log" "$RUN"/base*.log 2>/dev/null | sed 's/^/   /' || true
if [ "$COMPARE" = 1 ]; then
    echo "== the same scans in one process (the composed run): its map against the base station's"
    mkdir -p "$RUN/composed"
    cat > "$WORK/composed.yaml" <<YAML
namespace: /robot
topics: {points: stream, keyframe: stream, local_map: stream}  # every scan, nothing dropped
components:
  - {name: player, type: kitti_player, params: {path: "$DATA", mode: fast}}
  - {name: odometry, type: odometry, params: {preset: $preset}}
  - {name: mapping, type: mapping, params: {preset: $preset, map_dir: "$RUN/composed/map"}}
YAML
    ip netns exec "$NS_BASE" "$BIN/ltm_host" "$WORK/composed.yaml" --set "$(dds lo 127.0.0.1)" \
        > "$RUN/composed.log" 2>&1 || die "the composed run failed (its log: $RUN/composed.log)"
    "$BIN/ltm_map_diff" "$RUN/composed/map" "$RUN/base/map" --tolerance 0.001 --require-same-loops \
        | sed 's/^/   /' || map_differs=1
    # Scans the robot's odometry did not process (real time on a shared machine) explain a
    # difference.
    grep -ho "[0-9]* scans skipped[^,;]*" "$RUN/robot.log" | tail -n 1 | sed 's/^/   robot: /' || true
fi
if [ "$SAME_MAP" = 1 ] && [ "${map_differs:-0}" = 1 ]; then
    echo "== FAILED: the base station's map is not the composed run's"
    exit 1
fi
if [ "${required_missing:-0}" = 1 ]; then
    echo "== FAILED: a message of ${REQUIRE[*]} did not reach the base station"
    exit 1
fi
