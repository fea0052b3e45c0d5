#!/usr/bin/env bash
# A shipped launch config stopped by a signal at one moment: the host must exit 0 with "stopped
# cleanly" within its stop deadline, list what it saved, and every output it lists must be there.
#   stop_config.sh LAUNCH.yaml SECONDS [--signal INT|TERM] [--keep DIR] [--set NAME.KEY=VALUE ...]
# SECONDS after the host reports its components running, SIGNAL (TERM by default) goes to the
# host. Inputs come from the checkout: the KITTI fixture (LTM_DATA), the site_loop scenario
# (LTM_SCENARIO), the small map of the map-file tests (LTM_MAP; localisation runs, lost, with
# global localisation). DDS stays on loopback on a domain of the run's own. Prints one line:
#   CONFIG  MOMENT  EXIT  STOP_S  ACTIVITY  SAVED
# and exits 0 only when the stop was clean. Used by ctest (one case a config) and by
# `./ltm bench stop` (the matrix).
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
usage() { echo "usage: stop_config.sh LAUNCH.yaml SECONDS [--signal INT|TERM] [--keep DIR] [--set NAME.KEY=VALUE ...]" >&2; exit 2; }
[ $# -ge 2 ] || usage
LAUNCH="$1"; AT="$2"; SIG=TERM; KEEP=""; SETS=()
shift 2
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || usage
    case "$1" in
        --signal) SIG="$2" ;;
        --keep) KEEP="$2" ;;
        --set) SETS+=(--set "$2") ;;
        *) usage ;;
    esac
    shift 2
done
[ -f "$LAUNCH" ] || LAUNCH="$ROOT/launch_configs/$LAUNCH"
[ -f "$LAUNCH" ] || { echo "stop_config.sh: no such launch config: $1" >&2; exit 2; }
[ -x "$BUILD/bin/ltm_host" ] || { echo "stop_config.sh: ltm_host is not built in $BUILD" >&2; exit 2; }
name="$(basename "$LAUNCH" .yaml)"
OUT="${KEEP:-$(mktemp -d "${TMPDIR:-/tmp}/ltm_stop_${name}.XXXXXX")}"
mkdir -p "$OUT"
host_pid=""
cleanup() {
    trap '' INT TERM  # a second signal must not cut the cleanup short
    [ -n "$host_pid" ] && kill -KILL "$host_pid" 2>/dev/null
    [ -n "$KEEP" ] || rm -rf "$OUT"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# A domain of this run's own (parallel tests do not meet): 100..199 from the pid.
domain=$((100 + $$ % 100))
log="$OUT/host.log"
mkdir -p "$OUT/maintenance"
LTM_ROOT="$ROOT" LTM_OUT="$OUT" LTM_DATA="$ROOT/tests/fixtures/kitti00_mini" \
    LTM_SCENARIO="$ROOT/components/simulator/scenarios/site_loop.yaml" \
    LTM_MAP="$ROOT/components/mapping/core/testdata/map_v2" \
    LTM_MAINTAINED_MAP="$OUT/maintenance/long_term_map.bin" LTM_RECORDING="$OUT/recording.mcap" \
    LTM_SITE="$OUT/site" \
    "$BUILD/bin/ltm_host" "$LAUNCH" --set "domain_id=$domain" --set 'dds.interfaces=[lo]' \
    --set 'dds.peers=[127.0.0.1]' --set dds.multicast=false "${SETS[@]}" > "$log" 2>&1 &
host_pid=$!

# Running: the host's line, then SECONDS more (a run that ends by itself before is not a stop).
for _ in $(seq 1 600); do
    grep -q "\[host\] running" "$log" && break
    kill -0 "$host_pid" 2>/dev/null || break
    sleep 0.1
done
grep -q "\[host\] running" "$log" || { echo "$name: the host did not start:"; tail -n 5 "$log"; exit 1; }
sleep "$AT"
kill -0 "$host_pid" 2>/dev/null || { echo "$name: the run ended by itself before ${AT} s:"; tail -n 5 "$log"; exit 1; }
t0=$(date +%s.%N)
kill -"$SIG" "$host_pid"
rc=0; wait "$host_pid" || rc=$?
host_pid=""
stop_s=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')

# What was running when the signal came (the host says so when a stop takes more than 5 s).
activity=$(grep -o "stopping: waiting for '[^']*' ([^)]*)" "$log" | head -n 1 | sed "s/stopping: waiting for //")
saved=$(grep -c "\] saved " "$log" || true)
fails=0
problem() { echo "  $*"; fails=$((fails + 1)); }
[ "$rc" = 0 ] || problem "exit status $rc (expected 0)"
grep -q "\[host\] stopped cleanly" "$log" || problem "no 'stopped cleanly'"
grep -q "NOT saved\|did not stop" "$log" && problem "$(grep -m1 "NOT saved\|did not stop" "$log")"
# Every output listed as saved is there and complete: a folder with files in it, a file (an empty
# trajectory is a complete one), a recording that ltm_mcap reads to its end, a PLY with its header.
while read -r path; do
    # Staged for a site's next version: the site component moved it there (the version is an
    # output of its own, checked like the others).
    case "$path" in
        */site/next/*) path="$(ls -d "$OUT"/site/versions/v* | tail -n 1)/${path#*/site/next/}" ;;
    esac
    if [ -d "$path" ]; then
        [ -n "$(ls -A "$path")" ] || problem "saved output $path is an empty folder"
    elif [ ! -f "$path" ]; then
        problem "saved output $path is missing"
    else
        case "$path" in
            *.mcap) "$BUILD/bin/ltm_mcap" info "$path" > /dev/null 2>&1 ||
                        problem "saved recording $path is not a complete MCAP file" ;;
            *.ply) head -c 4096 "$path" | grep -aq '^end_header' ||
                       problem "saved PLY $path has no complete header" ;;
        esac
    fi
done < <(sed -n 's/.*\] saved [^:]*: \([^ ]*\).*/\1/p' "$log")
printf '%-28s %5s s  %-4s exit %-3s stop %5s s  %-40s %s outputs saved\n' "$name" "$AT" "SIG$SIG" "$rc" \
    "$stop_s" "${activity:-(nothing still running)}" "$saved"
if [ "$fails" -gt 0 ]; then
    echo "  the host's last lines ($log):"; tail -n 12 "$log" | sed 's/^/    /'
    exit 1
fi
