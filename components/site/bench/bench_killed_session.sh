#!/usr/bin/env bash
# components/site/bench/bench_killed_session.sh --out DIR [--scenario S]: a lifelong session
# killed with SIGKILL, then the same day again, through launch_configs/robot_lifelong.yaml (the
# host, the real components). Day 0 commits v0001; day 1 is killed (kill -9 of its host) as soon
# as its mapping has saved into the staging (SITE/next); day 1 again must remove the killed
# session's staging (the log names its pid), keep its own and commit v0002. Prints what the
# killed session left and the restarted day's staging lines; `ltm_site versions` at the end.
# DDS domain: LTM_BENCH_DOMAIN (default 47); the Foxglove bridge on port 8797.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
DOMAIN="${LTM_BENCH_DOMAIN:-47}"
SCENARIO="$ROOT/components/simulator/scenarios/tiny_week.yaml"
OUT=""
while [ $# -gt 0 ]; do
    case "$1" in
        --out | --scenario)
            [ $# -ge 2 ] || { echo "bench killed_session: $1: needs a value" >&2; exit 2; }
            [ "$1" = --out ] && OUT="$2" || SCENARIO="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
            shift 2 ;;
        *) echo "bench killed_session: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
[ -n "$OUT" ] || { echo "usage: bench_killed_session.sh --out DIR [--scenario S]" >&2; exit 2; }
[ -x "$BUILD/bin/ltm_host" ] || { echo "bench killed_session: $BUILD/bin/ltm_host is not built" >&2; exit 2; }
rm -rf "$OUT" && mkdir -p "$OUT" && OUT="$(cd "$OUT" && pwd)"
cd "$ROOT" || exit 2

day() {  # day SESSION FOLDER
    LTM_BUILD_DIR="$BUILD" LTM_SITE="$OUT/site" LTM_SCENARIO="$SCENARIO" LTM_OUT="$OUT/$2" \
        ./ltm run launch_configs/robot_lifelong.yaml --set domain_id="$DOMAIN" \
        --set sensor.session="$1" --set bridge.port=8797 --out "$OUT/$2" > "$OUT/$2.log" 2>&1
}

day 0 day0; echo "day 0: exit $?"
day 1 day1-killed &
runner=$!
for _ in $(seq 1 1200); do
    grep -q "map saved to $OUT/site/next/map" "$OUT/day1-killed.log" 2>/dev/null && break
    sleep 0.1
done
host=$(pgrep -n -f "ltm_host .*domain_id=$DOMAIN " || true)
[ -n "$host" ] || { echo "bench killed_session: no host of day 1 to kill" >&2; exit 1; }
kill -KILL "$host"
wait "$runner"
echo "day 1: host $host killed (SIGKILL) after $(grep -c 'map saved to' "$OUT/day1-killed.log") save(s)"
echo "  left in SITE/next: $(find "$OUT/site/next" -type f | wc -l) files; its marker:"
sed 's/^/    /' "$OUT/site/next/session"
day 1 day1; echo "day 1 again: exit $?"
grep -h "removed .*next\|is this session's staging\|saved site version" "$OUT/day1.log"
"$BUILD/bin/ltm_site" versions "$OUT/site"
