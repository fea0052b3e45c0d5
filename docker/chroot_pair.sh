#!/usr/bin/env bash
# The robot and base-station images end to end where no container may run: each image's entry
# point from its exported file system by chroot (./ltm image run --chroot), each in its own network
# namespace, joined by a veth pair and talking unicast DDS as on a site's link (docker/README.md).
#   docker/chroot_pair.sh [--data DIR] [--domain N] [--results DIR] [--robot-set K=V ...]
# DIR: scans in KITTI layout for the robot (default: the three KITTI 00 scans in the image). Prints
# the time from the robot's start to the base station's first local map and each side's exit.
# Root only; the namespaces go at exit.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
die() { printf 'chroot_pair: error: %s\n' "$*" >&2; exit 1; }
data="" domain=64 results="$PWD/results/image-pair-$(date +%Y%m%d-%H%M%S)" robot_set=()
while [ $# -gt 0 ]; do
    case "$1" in
        --data) [ $# -ge 2 ] || die "--data needs a folder"; data="$2"; shift 2 ;;
        --domain) [ $# -ge 2 ] || die "--domain needs a number"; domain="$2"; shift 2 ;;
        --results) [ $# -ge 2 ] || die "--results needs a folder"; results="$2"; shift 2 ;;
        --robot-set) [ $# -ge 2 ] || die "--robot-set needs NAME.KEY=VALUE"; robot_set+=(--set "$2"); shift 2 ;;
        -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown argument '$1' (--help)" ;;
    esac
done
[ "$(id -u)" = 0 ] || die "root only (network namespaces, chroot)"
mkdir -p "$results/robot" "$results/base_station"
results="$(realpath "$results")"
NS_R="ltm_img_robot_$$" NS_B="ltm_img_base_$$" DEV_R="ltmir$$" DEV_B="ltmib$$"
ADDR_R=10.231.0.1 ADDR_B=10.231.0.2
PIDS=()
cleanup() {
    local p
    for p in "${PIDS[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
    for p in "${PIDS[@]}"; do wait "$p" 2>/dev/null || true; done
    ip netns del "$NS_R" 2>/dev/null || true
    ip netns del "$NS_B" 2>/dev/null || true
}
trap cleanup EXIT
ip netns add "$NS_R" && ip netns add "$NS_B" || die "cannot create network namespaces here"
ip link add "$DEV_R" type veth peer name "$DEV_B" || die "cannot create a veth pair"
ip link set "$DEV_R" netns "$NS_R" && ip link set "$DEV_B" netns "$NS_B"
ip -n "$NS_R" addr add "$ADDR_R/24" dev "$DEV_R" && ip -n "$NS_R" link set "$DEV_R" up && ip -n "$NS_R" link set lo up
ip -n "$NS_B" addr add "$ADDR_B/24" dev "$DEV_B" && ip -n "$NS_B" link set "$DEV_B" up && ip -n "$NS_B" link set lo up
link() { echo --set "dds.interfaces=[$1]" --set "dds.peers=[$2]" --set dds.multicast=false; }

start=$(date +%s.%N)
# shellcheck disable=SC2046
"$ROOT/ltm" image run base-station --chroot --netns "$NS_B" --results "$results/base_station" -- \
    /opt/ltm/launch_configs/base_station.yaml --set "domain_id=$domain" $(link "$DEV_B" "$ADDR_R") \
    > "$results/base_station.log" 2>&1 &
PIDS+=($!)
base_pid=$!
robot_args=(--chroot --netns "$NS_R" --results "$results/robot")
[ -z "$data" ] || robot_args+=(--data "$data")
# shellcheck disable=SC2046
"$ROOT/ltm" image run robot "${robot_args[@]}" -- /opt/ltm/launch_configs/robot.yaml \
    --set "domain_id=$domain" $(link "$DEV_R" "$ADDR_B") "${robot_set[@]}" > "$results/robot.log" 2>&1 &
PIDS+=($!)
robot_pid=$!
echo "chroot_pair: robot ($NS_R, $ADDR_R) and base station ($NS_B, $ADDR_B) on DDS domain $domain; logs and results in $results"
first=""
while kill -0 "$base_pid" 2>/dev/null; do
    if [ -z "$first" ] && compgen -G "$results/base_station/maps/local_map_*.ply" > /dev/null; then
        first="$(echo "$(date +%s.%N) - $start" | bc)"
        printf 'chroot_pair: first local map at the base station %.1f s after the start\n' "$first"
    fi
    sleep 0.2
done
wait "$robot_pid"; robot_rc=$?
wait "$base_pid"; base_rc=$?
PIDS=()
total="$(echo "$(date +%s.%N) - $start" | bc)"
[ -n "$first" ] || echo "chroot_pair: no local map reached the base station"
printf 'chroot_pair: robot exit %s (%s), base station exit %s (%s), %.1f s in all\n' \
    "$robot_rc" "$(grep -c 'stopped cleanly' "$results/robot.log") x stopped cleanly" \
    "$base_rc" "$(grep -c 'stopped cleanly' "$results/base_station.log") x stopped cleanly" "$total"
grep -E '\[(odometry|uplink|downlink|mapping)\] .*(scans|packets|keyframes)' "$results/robot.log" "$results/base_station.log" |
    sed "s|$results/||" | tail -n 6
echo "chroot_pair: base station wrote $(compgen -G "$results/base_station/maps/local_map_*.ply" | wc -l) local maps, $(wc -l < "$results/base_station/odometry.txt" 2>/dev/null || echo 0) odometry poses"
[ "$robot_rc" = 0 ] && [ "$base_rc" = 0 ] && [ -n "$first" ]
