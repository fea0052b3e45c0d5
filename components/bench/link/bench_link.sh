#!/usr/bin/env bash
# ./ltm bench link [--loss PCT] [--loss-on in|out|both] [--rate MBIT] [--outage S@T ...]
#                  [--linger S] [--drain S] [--scenario FILE] [--frames A:B] [--out DIR] [--require TOPIC ...]
#                  [--restart-base T] [--compare] [--require-same-map] [--robots N] [--security]
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
# Runs from a copy: bash reads a script as it goes, and a run takes minutes (a checkout or an edit
# meanwhile must not change what the running one executes).
if [ -z "${LTM_BENCH_LINK_ROOT:-}" ]; then
    copy="$(mktemp)"; cp "${BASH_SOURCE[0]}" "$copy"
    LTM_BENCH_LINK_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)" LTM_BENCH_LINK_COPY="$copy" \
        exec bash "$copy" "$@"
fi
ROOT="$LTM_BENCH_LINK_ROOT"
[ -n "${LTM_BENCH_LINK_COPY:-}" ] && rm -f "$LTM_BENCH_LINK_COPY"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
BIN="$BUILD/bin"
LOSS=0; LOSS_ON=both; RATE=0; SCENARIO="$ROOT/components/simulator/scenarios/tiny_loop.yaml"
LINGER=""; DRAIN=3; FRAMES=""; OUT=""; OUTAGES=(); REQUIRE=(); TOPICS=(odometry keyframe local_map)
RESTART=""; COMPARE=0; SAME_MAP=0; ROBOTS=1; SECURITY=0; INTRUDER=0; ROBOT_SETS=()
usage() {
    echo "Robot and base station in two network namespaces over a veth link with loss, a rate"
    echo "limit and outages; per topic what was sent and delivered, the bytes on the link"
    printf 'Usage: ./ltm bench link [OPTIONS]\n\nOptions:\n'
    printf '  %-24s%s\n' "-h,--help" "Print this help message and exit" \
        "--loss PCT=0" "packets dropped at random [%] (0..100, two decimals)" \
        "--loss-on in|out|both" "where on the base station: ingress, egress or both (both)" \
        "--rate MBIT=0" "tc tbf rate of each direction [Mbit/s] (0: unlimited)" \
        "--outage S@T" "drop everything for S s from T s after the robot starts (repeatable)" \
        "--linger S" "the robots' writers wait S s for acknowledgements at exit (robot.yaml: 5 s)" \
        "--drain S=$DRAIN" "the base station keeps listening S s after the robot exited" \
        "--scenario FILE" "simulator scenario (default tiny_loop)" \
        "--frames A:B" "scans A..B-1 of the scenario's session 0 (default all)" \
        "--out DIR" "keep the run here (default: a temporary folder, removed)" \
        "--require TOPIC" "exit 1 unless every message of TOPIC arrived (repeatable)" \
        "--restart-base T" "kill the base station T s after the robot started, start it again" \
        "--compare" "also run the scans in one process; compare its map with the base station's" \
        "--require-same-map" "with --compare: exit 1 unless anchors agree to 1 mm, same loops" \
        "--robots N=1" "robots (namespaces /robot1.. on links of their own; robot i drives session i-1)" \
        "--security" "DDS Security on every participant; an intruder without credentials listens" \
        "--intruder" "a participant of no robot on a link of its own records what it hears" \
        "--robot-set NAME.KEY=V" "a --set for each robot's host (odometry.* ones for the composed run too)"
}
fail() { echo "ltm bench link: $*" >&2; exit 2; }   # a wrong command line
die() { echo "ltm bench link: $*" >&2; exit 1; }    # the machine cannot do it
number='^[0-9]+([.][0-9]+)?$'
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --compare) COMPARE=1; shift; continue ;;
        --security) SECURITY=1; INTRUDER=1; shift; continue ;;
        --intruder) INTRUDER=1; shift; continue ;;
        --require-same-map) COMPARE=1; SAME_MAP=1; shift; continue ;;
        --loss|--loss-on|--rate|--outage|--linger|--drain|--scenario|--frames|--out|--require|--restart-base|--robots|--robot-set)
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
                --robot-set) [[ "$2" == *.*=* ]] || fail "--robot-set: expected NAME.KEY=VALUE, got '$2'"
                             ROBOT_SETS+=(--set "$2") ;;
                --robots) [[ "$2" =~ ^[1-9]$ ]] || fail "--robots: expected 1..9, got '$2'"
                          ROBOTS="$2" ;;
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

# Names unique to this run, so that two runs (or a stale one) do not meet. The base station's
# namespace holds a bridge; each robot (and, with --security, an intruder without credentials)
# has its own namespace and a veth pair to that bridge: its own link, broken on its own port.
TAG="$$"
NS_BASE="ltm_base_$TAG"; BRIDGE="ltmbr$TAG"; ADDR_BASE=10.77.0.254
NS_R=(); DEV_R=(); DEV_B=(); ADDR_R=(); NAME_R=()
for i in $(seq 1 "$ROBOTS"); do
    if [ "$ROBOTS" = 1 ]; then NS_R+=("ltm_robot_$TAG"); NAME_R+=(robot); else NS_R+=("ltm_robot${i}_$TAG"); NAME_R+=("robot$i"); fi
    DEV_R+=("ltmr${TAG}x$i"); DEV_B+=("ltmb${TAG}x$i"); ADDR_R+=("10.77.0.$i")
done
NS_X="ltm_intruder_$TAG"; DEV_XR="ltmi${TAG}x"; DEV_XB="ltmj${TAG}x"; ADDR_X=10.77.0.200
WORK="$(mktemp -d)"
PIDS=()
# Stops everything this run started and removes its namespaces and links, whatever happened
# (its own failure, a signal: SIGINT from timeout comes twice, to the script and to its group).
cleanup() {
    # A second signal must not cut the cleanup short (it did under load: namespaces were left).
    trap '' INT TERM
    local pid ns left=() waited=0
    # Every process of the run's namespaces too: one started just before the signal may not be
    # in PIDS yet.
    for ns in "${NS_R[@]}" "$NS_BASE" "$NS_X"; do
        for pid in $(ip netns pids "$ns" 2>/dev/null); do PIDS+=("$pid"); done
    done
    for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
    # The hosts save and stop within their deadline (the base station's: 60 s); then SIGKILL.
    while :; do
        left=()
        for pid in "${PIDS[@]}"; do kill -0 "$pid" 2>/dev/null && left+=("$pid"); done
        [ ${#left[@]} -eq 0 ] && break
        if [ "$waited" -ge 900 ]; then
            echo "ltm bench link: ${#left[@]} process(es) did not stop within 90 s: killed" >&2
            for pid in "${left[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
            break
        fi
        sleep 0.1; waited=$((waited + 1))
    done
    for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
    for ns in "${NS_R[@]}" "$NS_BASE" "$NS_X"; do ip netns del "$ns" 2>/dev/null || true; done
    for dev in "${DEV_R[@]}" "$DEV_XR"; do ip link del "$dev" 2>/dev/null || true; done  # when a move failed
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Namespaces of an earlier run that could not clean up (SIGKILL, e.g. a test runner's timeout):
# their veth ends, bridge and nftables table go with them. A run's pid is in its names.
for ns in $(ip netns list 2>/dev/null | awk '{print $1}' | grep -E '^ltm_(robot[0-9]*|base|intruder)_[0-9]+$'); do
    pid="${ns##*_}"
    if ! kill -0 "$pid" 2>/dev/null; then
        ip netns del "$ns" 2>/dev/null && echo "   removed namespace $ns of an earlier run (pid $pid is gone)"
    fi
done
ip netns add "$NS_BASE" 2>/dev/null || die "cannot create a network namespace (ip netns add failed): not available here"
ip -n "$NS_BASE" link set lo up
err="$(ip netns exec "$NS_BASE" true 2>&1)" ||
    die "cannot enter a network namespace here (ip netns exec: ${err//$'\n'/ }): a chroot whose / is no mount point?"
ip -n "$NS_BASE" link add "$BRIDGE" type bridge || die "cannot create a bridge"
ip -n "$NS_BASE" addr add "$ADDR_BASE/24" dev "$BRIDGE"
ip -n "$NS_BASE" link set "$BRIDGE" up
# join NS DEV_NS DEV_BASE ADDR: a namespace with its end of a veth pair, the other end on the bridge.
join() {
    ip netns add "$1" || die "cannot create network namespace $1"
    ip -n "$1" link set lo up
    ip link add "$2" type veth peer name "$3" || die "cannot create a veth pair"
    ip link set "$2" netns "$1"
    ip link set "$3" netns "$NS_BASE"
    ip -n "$1" addr add "$4/24" dev "$2"
    ip -n "$1" link set "$2" up
    ip -n "$NS_BASE" link set "$3" master "$BRIDGE"
    ip -n "$NS_BASE" link set "$3" up
}
for i in "${!NS_R[@]}"; do join "${NS_R[$i]}" "${DEV_R[$i]}" "${DEV_B[$i]}" "${ADDR_R[$i]}"; done
[ "$INTRUDER" = 1 ] && join "$NS_X" "$DEV_XR" "$DEV_XB" "$ADDR_X"

# Loss: numgen random drops of Ethernet frames (IP fragments one by one, as a radio loses them) on
# the base station's end of each robot's veth: netdev ingress (robot -> base) and egress
# (base -> robot). The outage chains come first (priority -10): an outage adds a drop-all rule.
nft_rules="add table netdev ltm_link
"
n=$(awk -v v="$LOSS" 'BEGIN {printf "%d", v * 100 + 0.5}')
for i in "${!NS_R[@]}"; do
    d="${DEV_B[$i]}"
    nft_rules+="add chain netdev ltm_link outage_in_$i { type filter hook ingress device \"$d\" priority -10; policy accept; }
add chain netdev ltm_link outage_out_$i { type filter hook egress device \"$d\" priority -10; policy accept; }
add chain netdev ltm_link in_$i { type filter hook ingress device \"$d\" priority 0; policy accept; }
add chain netdev ltm_link out_$i { type filter hook egress device \"$d\" priority 0; policy accept; }
"
    if [ "$n" -gt 0 ]; then
        [ "$LOSS_ON" = out ] || nft_rules+="add rule netdev ltm_link in_$i numgen random mod 10000 < $n counter drop
"
        [ "$LOSS_ON" = in ] || nft_rules+="add rule netdev ltm_link out_$i numgen random mod 10000 < $n counter drop
"
    fi
done
ip netns exec "$NS_BASE" nft -f - <<< "$nft_rules" || die "nft could not load the link rules (no nf_tables netdev hooks in this kernel?)"
if awk -v v="$RATE" 'BEGIN {exit !(v > 0)}'; then
    # tbf on both ends of each link: a burst of 10 ms at the rate (at least 16 KiB), 100 ms of queue.
    burst=$(awk -v r="$RATE" 'BEGIN {b = r * 1e6 / 8 / 100; if (b < 16384) b = 16384; printf "%d", b}')
    for i in "${!NS_R[@]}"; do
        ip netns exec "${NS_R[$i]}" tc qdisc add dev "${DEV_R[$i]}" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms \
            || die "tc tbf is not available"
        ip netns exec "$NS_BASE" tc qdisc add dev "${DEV_B[$i]}" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms
    done
fi

# The scenario as KITTI folders, robot i driving session i-1 (one robot: session 0); the odometry
# and mapping presets follow its sensor.
DATA=()
for i in "${!NS_R[@]}"; do
    DATA+=("$WORK/data$((i + 1))")
    sim_args=(--quiet --out "${DATA[$i]}" --session "$i")
    [ -n "$FRAMES" ] && sim_args+=(--frames "$FRAMES")
    "$BIN/ltm_sim" "${sim_args[@]}" "$SCENARIO" > "$WORK/sim$i.log" 2>&1 \
        || die "the simulator failed on session $i of $SCENARIO: $(tail -n 1 "$WORK/sim$i.log")"
done
model=$(awk '/^ *model:/ {print $2; exit}' "${DATA[0]}/scenario.yaml")
# The simulator's models and ltm's presets (common/core/sensor_preset.cpp: simulator_model).
case "$model" in
    hdl64e) preset=hdl64 ;; vlp32c) preset=vlp32 ;; vlp16) preset=vlp16 ;; os1_64) preset=os1-64 ;;
    livox_avia | solid_state) preset=narrow ;;
    *) die "no sensor preset for the simulator's model '$model' (common/core/sensor_preset.cpp)" ;;
esac
scans=$(wc -l < "${DATA[0]}/times.txt")

RUN="${OUT:-$WORK/run}"
mkdir -p "$RUN"
RUN="$(cd "$RUN" && pwd)"
rm -rf "$RUN"/robot* "$RUN/base" "$RUN/composed" "$RUN/intruder"
rm -f "$RUN"/*.log
# Each launch config with a recorder in its own process (what the robot's odometry published; what
# the base station's mapping was given), so the recording adds no traffic.
with_recorder() {
    cat "$1"
    printf '  - name: link_recorder\n    type: recorder\n    params: {file: "%s", topics: %s, compression: none}\n' \
        "$2" "$3"
}
with_recorder "$ROOT/launch_configs/robot.yaml" '${LTM_OUT}/sent.mcap' \
    "[odometry, onboard/keyframe, onboard/local_map]" > "$WORK/robot.yaml"
if [ "$ROBOTS" = 1 ]; then
    with_recorder "$ROOT/launch_configs/base_station.yaml" '${LTM_RECORDING}' \
        "[odometry, keyframe, local_map]" > "$WORK/base.yaml"
else
    # base_station_multi.yaml names robot1 and robot2: its robot1 lines and entries are repeated
    # for every robot, its robot2 ones dropped, the mapping's list rewritten.
    list=$(printf 'robot%s, ' $(seq 1 "$ROBOTS") | sed 's/, $//')
    awk -v n="$ROBOTS" -v list="$list" '
        function flush(   i, b) { if (block == "") return
            if (bname ~ /robot2/) { block = ""; return }
            if (bname ~ /robot1/) { for (i = 1; i <= n; i++) { b = block; gsub(/robot1/, "robot" i, b); printf "%s", b } }
            else printf "%s", block
            block = "" }
        /^  - name:/ { flush(); inblock = 1; bname = $0 }
        /^[a-z_]+:/ { flush(); inblock = 0 }
        inblock { line = $0; sub(/robots: \[robot1, robot2\]/, "robots: [" list "]", line); block = block line "\n"; next }
        /^#/ { print; next }
        /robot2/ { next }
        /robot1/ { for (i = 1; i <= n; i++) { l = $0; gsub(/robot1/, "robot" i, l); print l }; next }
        { print }
        END { flush() }' "$ROOT/launch_configs/base_station_multi.yaml" > "$WORK/base_multi.yaml"
    base_topics=$(for r in "${NAME_R[@]}"; do printf '/%s/odometry, /%s/keyframe, /%s/local_map, ' "$r" "$r" "$r"; done | sed 's/, $//')
    with_recorder "$WORK/base_multi.yaml" '${LTM_RECORDING}' "[$base_topics]" > "$WORK/base.yaml"
fi
# A host's interface and unicast peers as dotted --sets: the launch config's link profile (the
# rest of its dds: block) stays as it is.
dds() { DDS=(--set "dds.interfaces=[$1]" --set "dds.peers=[$2]" --set dds.multicast=false); }
linger_set=()
[ -n "$LINGER" ] && linger_set=(--set "dds.writer_linger_s=$LINGER")
# DDS Security: the site's certificates (the base station and every robot; not the intruder).
security_set=()
if [ "$SECURITY" = 1 ]; then
    command -v openssl >/dev/null || die "openssl is not installed: run ./ltm setup"
    bash "$ROOT/launch_configs/security/make_site_certs.sh" "$WORK/certs" "${NAME_R[@]}" > "$WORK/certs.log" 2>&1 \
        || die "make_site_certs.sh failed: $(tail -n 1 "$WORK/certs.log")"
    security_set=(--set "dds.security=$(cat "$ROOT/launch_configs/security/dds_security.yaml")")
fi

rate_text="$RATE Mbit/s"; [ "$rate_text" = "0 Mbit/s" ] && rate_text=unlimited
echo "== link: loss $LOSS % ($LOSS_ON), rate $rate_text, outages: ${OUTAGES[*]:-none}${RESTART:+, base station restarted at $RESTART s}, ${ROBOTS} robot(s)$([ "$SECURITY" = 1 ] && echo ", DDS Security on")"
echo "   scenario $(basename "$SCENARIO") ${FRAMES:+frames $FRAMES }($scans scans, $model), run in $RUN"
robot_peers=$(printf '%s, ' "${ADDR_R[@]}" | sed 's/, $//')
start_base() {  # start_base N: the Nth start of the base station (its own recording and log)
    local suffix=""; [ "$1" -gt 1 ] && suffix="$1"
    BASE_RECORDING="$RUN/base/delivered$suffix.mcap"
    dds "$BRIDGE" "$robot_peers"
    ip netns exec "$NS_BASE" env LTM_ROOT="$ROOT" LTM_OUT="$RUN/base" LTM_SITE="$RUN/base/site" LTM_RECORDING="$BASE_RECORDING" \
        LTM_SECURITY_DIR="$WORK/certs" LTM_PARTICIPANT=base_station \
        "$BIN/ltm_host" "$WORK/base.yaml" "${DDS[@]}" "${security_set[@]}" \
        --set "mapping.preset=$preset" --set idle_exit_s=0 --set shutdown_timeout_s=60 \
        >> "$RUN/base$suffix.log" 2>&1 &
    base_pid=$!; PIDS+=("$base_pid")
}
start_base 1
if [ "$INTRUDER" = 1 ]; then
    # A participant without the site's credentials on a link of its own: it records every topic
    # of the domain it can see.
    dds "$DEV_XR" "$ADDR_BASE, $robot_peers"
    ip netns exec "$NS_X" env LTM_ROOT="$ROOT" "$BIN/ltm_host" "$ROOT/launch_configs/tools/recorder.yaml" \
        "${DDS[@]}" --set "recorder.file=$RUN/intruder/heard.mcap" \
        --set recorder.all=true > "$RUN/intruder.log" 2>&1 &
    intruder_pid=$!; PIDS+=("$intruder_pid")
    mkdir -p "$RUN/intruder"
    if [ "$SECURITY" = 0 ]; then
        # Without security the intruder must be listening before the robots start: on a loaded
        # machine its discovery outlasted a short run and it heard nothing (a false failure of
        # the control case). It sees the base station's topics first (up to 60 s).
        for _ in $(seq 1 600); do
            grep -q "\[recorder\] recording" "$RUN/intruder.log" 2>/dev/null && break
            sleep 0.1
        done
    fi
fi
sleep 1
start=$(date +%s.%N)
ROBOT_PIDS=()
for i in "${!NS_R[@]}"; do
    ns_set=(); [ "$ROBOTS" -gt 1 ] && ns_set=(--set "namespace=/${NAME_R[$i]}")
    mkdir -p "$RUN/${NAME_R[$i]}"
    dds "${DEV_R[$i]}" "$ADDR_BASE"
    ip netns exec "${NS_R[$i]}" env LTM_ROOT="$ROOT" LTM_DATA="${DATA[$i]}" LTM_OUT="$RUN/${NAME_R[$i]}" LTM_SITE="$RUN/${NAME_R[$i]}/site" \
        LTM_SECURITY_DIR="$WORK/certs" LTM_PARTICIPANT="${NAME_R[$i]}" \
        "$BIN/ltm_host" "$WORK/robot.yaml" "${DDS[@]}" "${linger_set[@]}" \
        "${ns_set[@]}" "${security_set[@]}" --set "odometry.preset=$preset" --set "keyframe_digest.preset=$preset" "${ROBOT_SETS[@]}" \
        > "$RUN/${NAME_R[$i]}.log" 2>&1 &
    ROBOT_PIDS+=("$!"); PIDS+=("$!")
done
for o in "${OUTAGES[@]}"; do
    (
        s="${o%@*}"; t="${o#*@}"
        sleep "$t"
        for i in "${!NS_R[@]}"; do
            printf 'add rule netdev ltm_link outage_in_%s counter drop\nadd rule netdev ltm_link outage_out_%s counter drop\n' "$i" "$i"
        done | ip netns exec "$NS_BASE" nft -f -
        sleep "$s"
        for i in "${!NS_R[@]}"; do
            ip netns exec "$NS_BASE" nft flush chain netdev ltm_link "outage_in_$i"
            ip netns exec "$NS_BASE" nft flush chain netdev ltm_link "outage_out_$i"
        done
        date +%H:%M:%S.%N > "$WORK/outage_end_$t"
    ) &
    PIDS+=("$!")
done
robots_running() { local p; for p in "${ROBOT_PIDS[@]}"; do kill -0 "$p" 2>/dev/null && return 0; done; return 1; }
if [ -n "$RESTART" ]; then
    sleep "$RESTART"
    if robots_running; then
        echo "   base station killed (SIGKILL) $RESTART s after the robots started; started again"
        kill -KILL "$base_pid" 2>/dev/null || true
        wait "$base_pid" 2>/dev/null || true
        start_base 2
    else
        echo "   --restart-base $RESTART: the robots had finished already; no restart"
    fi
fi
robot_rc=0
for p in "${ROBOT_PIDS[@]}"; do wait "$p" || robot_rc=$?; done
robot_end=$(date +%s.%N)
# The base station runs until the robots are gone and DRAIN s more (not an idle timer: a discovery
# slowed by loss would stop it before the first message), then stops cleanly (maps saved).
sleep "$DRAIN"
kill -TERM "$base_pid" 2>/dev/null || true
base_rc=0; wait "$base_pid" || base_rc=$?
[ "$INTRUDER" = 1 ] && { kill -TERM "$intruder_pid" 2>/dev/null || true; wait "$intruder_pid" 2>/dev/null || true; }
[ "$robot_rc" -eq 0 ] || { echo "   a robot exited with $robot_rc:"; tail -n 3 "$RUN"/robot*.log; }
[ "$base_rc" -eq 0 ] || { echo "   base station exited with $base_rc:"; tail -n 3 "$RUN/base.log"; }
if [ "$robot_rc" -ne 0 ] || [ "$base_rc" -ne 0 ]; then die "a side of the link failed (its last lines above)"; fi
awk -v a="$start" -v b="$robot_end" 'BEGIN {printf "   robots ran %.1f s\n", b - a}'

# Bytes on each link: the veth counters of the robot's end (TX: robot -> base, RX: base -> robot);
# per km: the path of the simulated ground truth (KITTI poses: x, y, z in columns 4, 8, 12).
echo "== link bytes (veth, robot end)"
for i in "${!NS_R[@]}"; do
    read -r rb rp tb tp < <(ip -n "${NS_R[$i]}" -s link show dev "${DEV_R[$i]}" |
        awk '/RX:/ {getline; rb=$1; rp=$2} /TX:/ {getline; tb=$1; tp=$2} END {print rb, rp, tb, tp}')
    km=$(awk 'NR > 1 {d += sqrt(($4 - x) ^ 2 + ($8 - y) ^ 2 + ($12 - z) ^ 2)} {x = $4; y = $8; z = $12}
              END {printf "%.4f", d / 1000}' "${DATA[$i]}/poses.txt")
    awk -v who="${NAME_R[$i]}" -v tb="$tb" -v tp="$tp" -v rb="$rb" -v rp="$rp" -v a="$start" -v b="$robot_end" -v km="$km" \
        'BEGIN {d = b - a; printf "   %s -> base: %d bytes in %d packets (%.2f Mbit/s over %.1f s", who, tb, tp, tb * 8 / d / 1e6, d
                if (km > 0) printf "; %.1f MB per km driven, %.0f m", tb / 1e6 / km, km * 1000
                printf ")\n   base -> %s: %d bytes in %d packets\n", who, rb, rp}'
done
# Frames dropped by the loss rules of each direction (outage drops are flushed with their rule).
dropped() {
    local i n=0 c
    for i in "${!NS_R[@]}"; do
        c=$(ip netns exec "$NS_BASE" nft list chain netdev ltm_link "${1}_$i" |
            awk '/counter packets/ {for (i = 1; i < NF; i++) if ($i == "packets") n += $(i + 1)} END {print n + 0}')
        n=$((n + c))
    done
    echo "$n"
}
echo "   frames dropped for loss: $(dropped in) robot -> base, $(dropped out) base -> robot"

echo "== per topic: sent by the robot, delivered to the base station (compared byte for byte)"
BASE_SIDE="${BASE_RECORDING%.mcap}"; BASE_SIDE="${BASE_SIDE#$RUN/}"
SENT_JSON=()
for side in "$BASE_SIDE" "${NAME_R[@]/%//sent}"; do
    [ -f "$RUN/$side.mcap" ] || die "no recording $RUN/$side.mcap (--out DIR keeps the logs)"
    "$BIN/ltm_mcap" manifest "$RUN/$side.mcap" -o "$RUN/$side.json"
    [ "$side" = "$BASE_SIDE" ] || SENT_JSON+=("$RUN/$side.json")
done
# One manifest line a message: topic, publish time (the writer's) and the CDR bytes. A message is
# delivered when the base station recorded the same topic and bytes (the downlink publishes again,
# so its publish time is its own); a second copy in the base station's recording is a duplicate
# (applied twice). One missing before the topic's first delivered message was published before
# the base station's reader was matched (discovery). The robot's recorder finds the topics by
# discovery too and can miss a topic's first message: what only the base station recorded counts
# as sent (and is reported). Late: delivered more than 1 s after the odometry published it (one
# clock: the same machine); for local maps the latency's median and maximum too.
awk -v req=" ${REQUIRE[*]} " '
    function field(name,   i, r) {
        i = index($0, "\"" name "\": \""); if (!i) return ""
        r = substr($0, i + length(name) + 5); return substr(r, 1, index(r, "\"") - 1)
    }
    function topic_of(t) { if (!(t in order)) { order[t] = ++nt; name[nt] = t } }
    function short(t,   s) { s = t; sub(/^[^\/]*\//, "", s); return s }
    !/"data_hex"/ || !/"topic"/ { next }
    { t = field("topic"); sub(/^rt\//, "", t); sub(/\/onboard\//, "/", t)
      p = field("publish_time"); l = field("log_time"); d = field("data_hex") }
    FNR == NR { key = t SUBSEP d; if (key in got) dup[t]++; got[key] = length(d) / 2; at[key] = l
                if (!(t in first) || p < first[t]) first[t] = p; next }
    {
        n++; topic[n] = t; pub[n] = p; sent[t]++; bytes[t] += length(d) / 2; topic_of(t)
        key = t SUBSEP d
        if (key in got) { ok[t]++; seen[key] = 1; ms = (at[key] - p) / 1e6
                          if (ms > 1000) slow[t]++
                          if (short(t) == "local_map") lat[++nl] = ms }
        else { miss[n] = 1 }
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
            printf "   %-17s sent %4d (%8.2f MiB)  delivered %4d  late %4d  missing %d", t, sent[t], bytes[t] / 1048576, ok[t] + 0, slow[t] + 0, sent[t] - ok[t]
            if (sent[t] > ok[t]) printf " (%d before the base station matched, %d after)", early, late
            if (unrec[t]) printf " [%d only in the base station'"'"'s recording]", unrec[t]
            if (dup[t]) printf " DUPLICATES %d", dup[t]
            printf "\n"
            if ((sent[t] > ok[t] || dup[t]) && index(req, " " short(t) " ")) bad = 1
        }
        if (nl > 0) {
            for (i = 1; i <= nl; i++) for (j = i + 1; j <= nl; j++) if (lat[j] < lat[i]) { x = lat[i]; lat[i] = lat[j]; lat[j] = x }
            printf "   local map latency (odometry -> base station mapping): median %.0f ms, max %.0f ms over %d\n", lat[int((nl + 1) / 2)], lat[nl], nl
        }
        exit bad
    }' "$RUN/$BASE_SIDE.json" "${SENT_JSON[@]}" || required_missing=1
awk -v end="$robot_end" '/"log_time"/ {i = index($0, "\"log_time\": \""); t = substr($0, i + 13, 19) + 0
                               if (t > last) last = t}
    END {if (last) printf "   last message received by the base station %.1f s %s the robots exited\n", \
             (last / 1e9 > end ? last / 1e9 - end : end - last / 1e9), (last / 1e9 > end ? "after" : "before")}' \
    "$RUN/$BASE_SIDE.json"
# Each outage: how long after the link came back each uplink's backlog was delivered (its log).
sod() { awk -F: '{printf "%.3f", $1 * 3600 + $2 * 60 + $3}' <<< "$1"; }
for o in "${OUTAGES[@]}"; do
    t="${o#*@}"; [ -f "$WORK/outage_end_$t" ] || continue
    back=$(sod "$(cut -c1-12 "$WORK/outage_end_$t")")
    for r in "${NAME_R[@]}"; do
        line=$(awk -v b="$back" '/\[uplink\] backlog delivered/ {split($1, h, ":"); s = h[1] * 3600 + h[2] * 60 + h[3]
                                                                if (s >= b) {print s - b; exit}}' "$RUN/$r.log")
        if [ -n "$line" ]; then
            printf '   outage %s: %s'"'"'s backlog was delivered %.1f s after the link came back\n' "$o" "$r" "$line"
        else
            echo "   outage $o: no 'backlog delivered' in $r.log after the link came back"
        fi
    done
done
# A base-station restart: how long after it the uplinks had delivered what it lacked.
if [ -n "$RESTART" ]; then
    for r in "${NAME_R[@]}"; do
        grep -h "\[uplink\] \(the base station restarted\|backlog delivered\)" "$RUN/$r.log" | sed "s/^/   $r: /" || true
    done
fi
# Scans each robot's odometry processed (its rate unchanged: every scan) and the link
# components' own account (their final lines).
for r in "${NAME_R[@]}"; do
    grep -h "\[odometry\].*scans" "$RUN/$r.log" | tail -n 1 | sed "s/^/   $r: /" || true
done
grep -h "uplink.*final\|downlink.*final" "$RUN"/robot*.log "$RUN"/base*.log 2>/dev/null | sed 's/^/   /' || true
if [ "$INTRUDER" = 1 ]; then
    heard=0
    if [ -f "$RUN/intruder/heard.mcap" ]; then
        "$BIN/ltm_mcap" manifest "$RUN/intruder/heard.mcap" -o "$RUN/intruder/heard.json"
        heard=$(grep -c '"data_hex"' "$RUN/intruder/heard.json" || true)
    fi
    topics_heard=$({ grep -o '"topic": "[^"]*"' "$RUN/intruder/heard.json" 2>/dev/null || true; } | sort -u | wc -l)
    echo "== a participant without credentials (its own namespace and link): $heard messages received on $topics_heard topics"
    [ "$SECURITY" = 1 ] && [ "$heard" != 0 ] && intruder_heard=1
fi
if [ "$COMPARE" = 1 ] && [ "$ROBOTS" = 1 ]; then
    echo "== the same scans in one process (the composed run): its map against the base station's"
    mkdir -p "$RUN/composed"
    # robot.yaml without its uplink (the odometry's outputs not remapped) and with a mapping: the
    # robot's own settings, the scans played as fast as the odometry takes them.
    awk '/^  - name:/ {skip = ($3 == "uplink" || $3 == "keyframe_digest" || $3 == "site_receiver")} skip {next}
         /remap: \{keyframe: onboard\// {next} {print}' "$ROOT/launch_configs/robot.yaml" > "$WORK/composed.yaml"
    printf '  - {name: mapping, type: mapping, params: {preset: %s, map_dir: "%s"}}\n' \
        "$preset" "$RUN/composed/map" >> "$WORK/composed.yaml"
    composed_sets=()
    for ((k = 1; k < ${#ROBOT_SETS[@]}; k += 2)); do
        case "${ROBOT_SETS[$k]}" in odometry.*) composed_sets+=(--set "${ROBOT_SETS[$k]}") ;; esac
    done
    dds lo 127.0.0.1
    ip netns exec "$NS_BASE" env LTM_ROOT="$ROOT" LTM_DATA="${DATA[0]}" LTM_OUT="$RUN/composed" \
        "$BIN/ltm_host" "$WORK/composed.yaml" "${DDS[@]}" --set player.mode=fast \
        --set 'topics={points: stream, keyframe: stream, local_map: stream}' \
        --set "odometry.preset=$preset" "${composed_sets[@]}" > "$RUN/composed.log" 2>&1 \
        || die "the composed run failed (its log: $RUN/composed.log)"
    "$BIN/ltm_map_diff" "$RUN/composed/map" "$RUN/base/map" --tolerance 0.001 --require-same-loops \
        | sed 's/^/   /' || map_differs=1
fi
if [ "$ROBOTS" -gt 1 ]; then
    # Each robot's corrected path against its ground truth: aligned alone (its own shape), and all
    # robots with one alignment (one map: a robot not joined to the others is off by its start).
    echo "== one map of ${ROBOTS} robots: the base station's corrected paths against the ground truth"
    ate() {  # ate EST REF: the aligned ATE RMSE [m]
        "$BIN/ltm_eval" traj --estimate "$1" --reference "$2" --format tum > "$WORK/ate.txt" 2>&1 || { echo nan; return; }
        awk '/^\[ate_se3_aligned\]/ {f = 1} f && /rmse/ {print $NF; exit}' "$WORK/ate.txt"
    }
    : > "$WORK/all_est.txt"; : > "$WORK/all_ref.txt"; total=0
    for i in "${!NS_R[@]}"; do
        r="${NAME_R[$i]}"; est="$RUN/base/slam_${r}_tum.txt"; ref="${DATA[$i]}/poses_tum.txt"
        path=$(awk 'NR > 1 {d += sqrt(($4 - x) ^ 2 + ($8 - y) ^ 2 + ($12 - z) ^ 2)} {x = $4; y = $8; z = $12} END {printf "%.1f", d}' "${DATA[$i]}/poses.txt")
        total=$(awk -v a="$total" -v b="$path" 'BEGIN {print a + b}')
        if [ ! -s "$est" ]; then echo "   $r: no corrected path from the base station ($est)"; continue; fi
        cat "$est" >> "$WORK/all_est.txt"; cat "$ref" >> "$WORK/all_ref.txt"
        awk -v r="$r" -v a="$(ate "$est" "$ref")" -v m="$path" \
            'BEGIN {printf "   %s: ATE %.3f m over its %.0f m path (%.2f %%)\n", r, a, m, (m > 0 ? 100 * a / m : 0)}'
    done
    sort -n -o "$WORK/all_est.txt" "$WORK/all_est.txt"; sort -n -o "$WORK/all_ref.txt" "$WORK/all_ref.txt"
    awk -v a="$(ate "$WORK/all_est.txt" "$WORK/all_ref.txt")" -v m="$total" \
        'BEGIN {printf "   all robots, one alignment: ATE %.3f m over %.0f m (%.2f %%)\n", a, m, (m > 0 ? 100 * a / m : 0)}'
    grep -h "\[mapping\].*\(joined\|sessions\)" "$RUN/base.log" | tail -n "$ROBOTS" | sed 's/^/   /' || true
fi
if [ "$SAME_MAP" = 1 ] && [ "${map_differs:-0}" = 1 ]; then
    echo "== FAILED: the base station's map is not the composed run's"
    exit 1
fi
if [ "${intruder_heard:-0}" = 1 ]; then
    echo "== FAILED: a participant without credentials received messages"
    exit 1
fi
if [ "${required_missing:-0}" = 1 ]; then
    echo "== FAILED: a message of ${REQUIRE[*]} did not reach the base station"
    exit 1
fi
