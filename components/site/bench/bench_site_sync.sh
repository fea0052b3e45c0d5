#!/usr/bin/env bash
# A site version from the base station to the robot over a lossy link (issue 26):
#   bench_site_sync.sh --site SITE [--robot-has V] [--loss PCT] [--rate MBIT] [--kill-robot-at S]
#                      [--chunk-kib K] [--level L] [--out DIR]
# SITE is a site with versions (e.g. a `./ltm bench lifelong --out D` run's D/site). The base
# station's site holds SITE's version V (default: the newest but one) and the newest (hard links
# of SITE's files, no copy); the robot's holds a copy of V (its own files). The base station runs
# `site_publisher`, the robot `site_receiver`, each in its own host; as root in two network
# namespaces joined by a veth pair with nftables `numgen random` drops of frames both ways on the
# base station's end (--loss) and tc tbf (--rate), as `./ltm bench link`; without root both on
# loopback with no loss (said so). --kill-robot-at S kills the robot's host (SIGKILL) S seconds
# after it started and starts it again: the transfer resumes from the chunks on its disk.
# Prints what the version holds, what the robot fetched, the bytes on the link, the time to the
# commit, and checks the robot's new version (ltm_site check) against the base station's files.
# LTM_BENCH_DOMAIN: the DDS domain (default 64).
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
DOMAIN="${LTM_BENCH_DOMAIN:-64}"
SITE="" HAS="" LOSS=0 RATE=0 KILL_AT="" CHUNK=16 LEVEL=3 OUT=""
die() { echo "bench_site_sync: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --site) SITE="$2"; shift 2 ;;
        --robot-has) HAS="$2"; shift 2 ;;
        --loss) LOSS="$2"; shift 2 ;;
        --rate) RATE="$2"; shift 2 ;;
        --kill-robot-at) KILL_AT="$2"; shift 2 ;;
        --chunk-kib) CHUNK="$2"; shift 2 ;;
        --level) LEVEL="$2"; shift 2 ;;
        --out) OUT="$2"; shift 2 ;;
        -h|--help) sed -n 2,17p "$0"; exit 0 ;;
        *) die "unknown argument '$1' (--help)" ;;
    esac
done
[ -d "$SITE/versions" ] || die "--site: $SITE has no versions/ (give a site folder)"
for exe in ltm_host ltm_site; do [ -x "$BIN/$exe" ] || die "$exe is not built in $BIN"; done
mapfile -t VERSIONS < <(ls "$SITE/versions" | grep -E '^v[0-9]+$' | sort)
[ "${#VERSIONS[@]}" -ge 2 ] || die "$SITE needs two versions at least"
NEWEST="${VERSIONS[-1]}"
[ -n "$HAS" ] || HAS="${VERSIONS[-2]}"
[ -d "$SITE/versions/$HAS" ] || die "--robot-has: $SITE has no $HAS"
WORK="${OUT:-$(mktemp -d /tmp/ltm_site_sync.XXXXXX)}"
rm -rf "$WORK/base" "$WORK/robot"; mkdir -p "$WORK/base/versions" "$WORK/robot/versions"
cp -al "$SITE/versions/$HAS" "$SITE/versions/$NEWEST" "$WORK/base/versions/" || die "cannot link $SITE into $WORK"
cp -a "$SITE/versions/$HAS" "$WORK/robot/versions/" || die "cannot copy $HAS"

NETNS=0
if [ "$(id -u)" -eq 0 ] && command -v nft >/dev/null && ip netns add "ltm_ssb_$$" 2>/dev/null; then
    NETNS=1
fi
TAG=$$ NS_B="ltm_ssb_$$" NS_R="ltm_ssr_$$" DEV_B="ltmsb$$" DEV_R="ltmsr$$"
PIDS=()
cleanup() {
    trap '' INT TERM
    for p in "${PIDS[@]}"; do kill -TERM "$p" 2>/dev/null; done
    sleep 1
    for p in "${PIDS[@]}"; do kill -KILL "$p" 2>/dev/null; done
    if [ "$NETNS" = 1 ]; then ip netns del "$NS_B" 2>/dev/null; ip netns del "$NS_R" 2>/dev/null; fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

ADDR_B=127.0.0.1 ADDR_R=127.0.0.1
PRE_B=() PRE_R=()  # ip netns exec NS: it execs the program (the pid is the host's)
if [ "$NETNS" = 1 ]; then
    ip netns add "$NS_R" || die "cannot create $NS_R"
    ip link add "$DEV_B" type veth peer name "$DEV_R" || die "cannot create a veth pair"
    ip link set "$DEV_B" netns "$NS_B"; ip link set "$DEV_R" netns "$NS_R"
    ADDR_B=10.78.0.1 ADDR_R=10.78.0.2
    ip -n "$NS_B" addr add "$ADDR_B/24" dev "$DEV_B"; ip -n "$NS_R" addr add "$ADDR_R/24" dev "$DEV_R"
    for ns in "$NS_B" "$NS_R"; do ip -n "$ns" link set lo up; done
    ip -n "$NS_B" link set "$DEV_B" up; ip -n "$NS_R" link set "$DEV_R" up
    n=$(awk -v v="$LOSS" 'BEGIN {printf "%d", v * 100 + 0.5}')
    rules="add table netdev ltm_sync
add chain netdev ltm_sync in { type filter hook ingress device \"$DEV_B\" priority 0; policy accept; }
add chain netdev ltm_sync out { type filter hook egress device \"$DEV_B\" priority 0; policy accept; }
"
    [ "$n" -gt 0 ] && rules+="add rule netdev ltm_sync in numgen random mod 10000 < $n counter drop
add rule netdev ltm_sync out numgen random mod 10000 < $n counter drop
"
    ip netns exec "$NS_B" nft -f - <<< "$rules" || die "nft could not load the loss rules"
    if awk -v v="$RATE" 'BEGIN {exit !(v > 0)}'; then
        burst=$(awk -v r="$RATE" 'BEGIN {b = r * 1e6 / 8 / 100; if (b < 16384) b = 16384; printf "%d", b}')
        ip netns exec "$NS_R" tc qdisc add dev "$DEV_R" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms || die "tc tbf failed"
        ip netns exec "$NS_B" tc qdisc add dev "$DEV_B" root tbf rate "${RATE}mbit" burst "$burst" latency 100ms
    fi
    PRE_B=(ip netns exec "$NS_B") PRE_R=(ip netns exec "$NS_R")
    IF_B="$DEV_B" IF_R="$DEV_R"
else
    echo "== not root or no network namespaces here: both ends on loopback, no loss, no rate"
    IF_B=lo IF_R=lo
fi

# The link's DDS profile of robot.yaml / base_station.yaml (one datagram a frame).
profile() {  # INTERFACE PEER
    cat <<YAML
domain_id: $DOMAIN
dds:
  interfaces: [$1]
  peers: [$2]
  multicast: false
  max_message_size: 1456 B
  fragment_size: 1344 B
  max_retransmit_message_size: 1456 B
  heartbeat_interval_s: 0.1
  nack_delay_s: 0.1
  socket_receive_buffer_size: 8 MiB
  whc_low: 4 MiB
  whc_high_init: 8 MiB
  whc_high: 16 MiB
  extra_xml: "<Discovery><SPDPInterval>1 s</SPDPInterval></Discovery>"
topics:
  site/offer: {role: map, depth: 1}
  site/request: {role: state, keep_all: true, depth: 64}
  site/chunk: {role: state, keep_all: true, depth: 64, max_blocking_s: 0.05}
YAML
}
{ profile "$IF_B" "$ADDR_R"; cat <<YAML
components:
  - name: site_publisher
    type: site_publisher
    params: {site_dir: $WORK/base, chunk_kib: $CHUNK, compression_level: $LEVEL}
YAML
} > "$WORK/base.yaml"
{ profile "$IF_R" "$ADDR_B"; cat <<YAML
components:
  - name: site_receiver
    type: site_receiver
    params: {site_dir: $WORK/robot, window_chunks: 64, resend_after_s: 5}
YAML
} > "$WORK/robot.yaml"

now() { date +%s.%N; }
bytes_of() {  # DEV -> "rx tx" (the robot's end)
    "${PRE_R[@]}" ip -s link show dev "$1" | awk '/RX:/ {getline; rb=$1} /TX:/ {getline; tb=$1} END {print rb, tb}'
}
echo "== base station: $WORK/base ($HAS, $NEWEST), robot: $WORK/robot ($HAS); loss ${LOSS} %, rate ${RATE} Mbit/s (0: none), chunks ${CHUNK} KiB, zstd level $LEVEL, domain $DOMAIN"
read -r r0 t0 < <(bytes_of "$IF_R")
"${PRE_B[@]}" "$BIN/ltm_host" "$WORK/base.yaml" > "$WORK/base.out" 2> "$WORK/base.log" & PIDS+=($!)
start=$(now)
"${PRE_R[@]}" "$BIN/ltm_host" "$WORK/robot.yaml" > "$WORK/robot.out" 2> "$WORK/robot.log" & RPID=$!; PIDS+=($RPID)
restarted=0
while :; do
    if grep -q "received $NEWEST from the base station" "$WORK/robot.log" "$WORK/robot.log.1" 2>/dev/null; then break; fi
    t=$(now)
    if [ -n "$KILL_AT" ] && [ "$restarted" = 0 ] && awk -v a="$start" -v b="$t" -v k="$KILL_AT" 'BEGIN {exit !(b - a >= k)}'; then
        kill -KILL "$RPID"; wait "$RPID" 2>/dev/null
        mv "$WORK/robot.log" "$WORK/robot.log.1"
        echo "   robot killed (SIGKILL) at ${KILL_AT} s; restarted"
        "${PRE_R[@]}" "$BIN/ltm_host" "$WORK/robot.yaml" > "$WORK/robot.out" 2> "$WORK/robot.log" & RPID=$!; PIDS+=($RPID)
        restarted=1
    fi
    if awk -v a="$start" -v b="$t" 'BEGIN {exit !(b - a > 1800)}'; then echo "   not received within 30 min"; break; fi
    kill -0 "$RPID" 2>/dev/null || { echo "   the robot's host exited:"; tail -5 "$WORK/robot.log"; break; }
    sleep 0.2
done
end=$(now)
read -r r1 t1 < <(bytes_of "$IF_R")
kill -TERM "${PIDS[@]}" 2>/dev/null
for p in "${PIDS[@]}"; do wait "$p" 2>/dev/null; done
echo "== robot"
grep -h -E "offers|kept from|received v|damaged|not whole|asked again|waits" "$WORK"/robot.log* | sed 's/^/   /' | cut -c1-260 | tail -8
echo "== base station"
grep -h -E "offering|final:" "$WORK/base.log" | sed 's/^/   /' | cut -c1-260
awk -v a="$start" -v b="$end" -v rx=$((r1 - r0)) -v tx=$((t1 - t0)) -v nn="$NETNS" 'BEGIN {
    d = b - a; printf "== link (%s): base -> robot %.2f MB, robot -> base %.2f MB in %.1f s (%.2f Mbit/s down)\n",
    nn ? "veth, robot end" : "loopback: every host on lo, not the link alone", rx / 1e6, tx / 1e6, d, rx * 8 / d / 1e6 }'
if [ "$NETNS" = 1 ]; then
    ip netns exec "$NS_B" nft list table netdev ltm_sync | awk '/counter packets/ {for (i = 1; i < NF; i++) if ($i == "packets") n += $(i + 1)} END {printf "   frames dropped by the loss rules: %d\n", n}'
fi
echo "== sizes: $NEWEST $(du -sb "$SITE/versions/$NEWEST" | cut -f1) bytes (with its hard-linked files)"
"$BIN/ltm_site" check "$WORK/robot" 2>&1 | sed 's/^/   /'
# Every file of the robot's new version is the base station's.
if diff <(cd "$WORK/base/versions/$NEWEST" && find . -type f -exec md5sum {} + | sort -k2) \
        <(cd "$WORK/robot/versions/$NEWEST" 2>/dev/null && find . -type f -exec md5sum {} + | sort -k2) >/dev/null; then
    echo "   $NEWEST on the robot: every file the base station's"
else
    echo "   $NEWEST on the robot differs from the base station's (or is missing)"; exit 1
fi
