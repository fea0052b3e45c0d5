#!/usr/bin/env bash
# ./ltm bench disk [--days N] [--budget-mb MB] [--seconds S] [--link "BENCH LINK ARGS"] [--out DIR]
# The disk over a long run (issue 28, item 4):
#  recordings: N "days" of a recorder (the KITTI fixture's scans looping at 30 Hz for S s a day,
#    one day folder each, as robot_lifelong.yaml records a day) with `budget_dir` over the days and
#    `max_total_mb`: the folder's size after each day, beside what it would hold without a budget.
#  link (--link, root): `./ltm bench link ARGS` with both journals sampled every second: the
#    robot's uplink backlog (pruned once acknowledged) and the base station's downlink journal
#    (kept: what a restarted base station replays), peak and end sizes.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
HOST="$BUILD/bin/ltm_host"
DOMAIN="${LTM_BENCH_DOMAIN:-63}"
DAYS=6; BUDGET=40; SECONDS_A_DAY=4; LINK=""; OUT=""
fail() { echo "ltm bench disk: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        --days|--budget-mb|--seconds|--link|--out)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --days) [[ "$2" =~ ^[1-9][0-9]*$ ]] || fail "--days: expected a count, got '$2'"; DAYS="$2" ;;
                --budget-mb) [[ "$2" =~ ^[0-9]+$ ]] || fail "--budget-mb: expected MiB, got '$2'"; BUDGET="$2" ;;
                --seconds) [[ "$2" =~ ^[1-9][0-9]*$ ]] || fail "--seconds: expected seconds, got '$2'"; SECONDS_A_DAY="$2" ;;
                --link) LINK="$2" ;;
                --out) OUT="$2" ;;
            esac
            shift 2 ;;
        *) fail "unknown option '$1' (--help)" ;;
    esac
done
[ -x "$HOST" ] || { echo "ltm bench disk: $HOST is not built (ninja -C $BUILD ltm_host)" >&2; exit 1; }
WORK="${OUT:-$(mktemp -d /tmp/ltm_bench_disk.XXXXXX)}"
mkdir -p "$WORK"
[ -n "$OUT" ] || trap 'rm -rf "$WORK"' EXIT
mib() { awk -v b="$1" 'BEGIN {printf "%.1f", b / 1048576}'; }

echo "recordings: $DAYS days of $SECONDS_A_DAY s, max_total_mb $BUDGET over $WORK/days"
printf '  %-5s %-16s %-18s %s\n' day "today's file" "folder (budget)" "all days (no budget)"
rm -rf "$WORK/days"
unbudgeted=0
for day in $(seq 1 "$DAYS"); do
    cat > "$WORK/day.yaml" <<EOT
domain_id: $DOMAIN
namespace: /robot
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
exit_when_sources_done: false
components:
  - name: player
    type: kitti_player
    params: {path: "$ROOT/tests/fixtures/kitti00_mini", loop: true, rate: 3}
  - name: recorder
    type: recorder
    params: {file: "$WORK/days/day$day/lifelong.mcap", topics: [points], budget_dir: "$WORK/days", max_total_mb: $BUDGET}
EOT
    "$HOST" "$WORK/day.yaml" > "$WORK/day$day.log" 2>&1 &
    pid=$!
    sleep "$SECONDS_A_DAY"
    kill -INT "$pid"; wait "$pid" || { echo "day $day: the host failed, $WORK/day$day.log"; exit 1; }
    today=$(stat -c %s "$WORK/days/day$day/lifelong.mcap")
    unbudgeted=$((unbudgeted + today))
    folder=$(find "$WORK/days" -name '*.mcap' -printf '%s\n' | awk '{s += $1} END {print s + 0}')
    printf '  %-5s %-16s %-18s %s\n' "$day" "$(mib "$today") MiB" "$(mib "$folder") MiB" "$(mib "$unbudgeted") MiB"
    # Sleep a second so that the days' files differ in time (the budget goes by modification time).
    sleep 1
done
for day in $(seq 1 "$DAYS"); do
    grep -h '\[recorder\] removed' "$WORK/day$day.log" | sed "s/^[^[]*/  day $day: /" || true
done

[ -n "$LINK" ] || exit 0
echo "link: ./ltm bench link $LINK, journals sampled every second"
mkdir -p "$WORK/link"
# shellcheck disable=SC2086
LTM_BENCH_DOMAIN="$DOMAIN" bash "$ROOT/components/bench/link/bench_link.sh" $LINK --out "$WORK/link" \
    > "$WORK/link.log" 2>&1 &
bench=$!
: > "$WORK/journals.tsv"
t=0
while kill -0 "$bench" 2>/dev/null; do
    # (the folders appear as the hosts start: du's complaint about a missing one is no error)
    up=$({ du -sb "$WORK"/link/robot*/uplink 2>/dev/null || true; } | awk '{s += $1} END {print s + 0}')
    down=$({ du -sb "$WORK"/link/base/downlink 2>/dev/null || true; } | awk '{s += $1} END {print s + 0}')
    printf '%s\t%s\t%s\n' "$t" "$up" "$down" >> "$WORK/journals.tsv"
    sleep 1; t=$((t + 1))
done
wait "$bench" || echo "  (bench link exited non-zero: $WORK/link.log)"
awk -F'\t' '{ if ($2 > pu) pu = $2; if ($3 > pd) pd = $3; n++; if ($1 % 15 == 0) rows = rows sprintf("  %5d s  %10.1f MiB  %10.1f MiB\n", $1, $2 / 1048576, $3 / 1048576); lu = $2; ld = $3 }
     END { printf "  %7s  %14s  %14s\n", "time", "robot backlog", "base journal"; printf "%s", rows
           printf "  peak     %10.1f MiB  %10.1f MiB\n  end      %10.1f MiB  %10.1f MiB\n", pu / 1048576, pd / 1048576, lu / 1048576, ld / 1048576 }' "$WORK/journals.tsv"
grep -E 'robot/(keyframe|local_map) +sent' "$WORK/link.log" | sed 's/^/  /' || true
