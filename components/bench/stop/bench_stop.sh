#!/usr/bin/env bash
# ./ltm bench stop [--configs "a b ..."] [--moments "S S ..."] [--signal INT|TERM] [--out DIR]
# Every shipped launch config stopped by a signal at several moments (tests/stop/stop_config.sh
# each time: the same inputs as the stop tests, DDS on loopback): per run the exit status, how
# long the stop took, what the host was still waiting for, the work that ended during the stop
# (a maintenance pass, a meshing, a global localisation, a map save: the components' own log
# lines between the signal and "stopped") and how many outputs were saved. Exit 1 when a stop
# was not clean.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
CONFIGS="robot_composed robot_maintain robot_localise robot_localise_maintain kitti_composed robot base_station base_station_multi replay"
MOMENTS="3 12 27"; SIG=""; OUT=""
usage() {
    echo "Every shipped launch config stopped by SIGTERM/SIGINT at several moments: exit status,"
    echo "stop time, what was running, outputs saved"
    printf 'Usage: ./ltm bench stop [OPTIONS]\n\nOptions:\n'
    printf '  %-22s%s\n' "-h,--help" "Print this help message and exit" \
        "--configs \"A B\"" "launch configs (default: every shipped one)" \
        "--moments \"S S\"" "seconds after the start (default: $MOMENTS)" \
        "--signal INT|TERM" "the signal (default: TERM and INT alternately)" \
        "--out DIR" "keep every run's folder and host.log here"
}
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --configs|--moments|--signal|--out)
            [ $# -ge 2 ] || { echo "ltm bench stop: $1: needs a value" >&2; exit 2; }
            case "$1" in
                --configs) CONFIGS="$2" ;;
                --moments) MOMENTS="$2" ;;
                --signal) case "$2" in INT|TERM) SIG="$2" ;; *) echo "ltm bench stop: --signal: INT or TERM, got '$2'" >&2; exit 2 ;; esac ;;
                --out) OUT="$2" ;;
            esac
            shift 2 ;;
        *) echo "ltm bench stop: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
OUT="${OUT:-$(mktemp -d "${TMPDIR:-/tmp}/ltm_bench_stop.XXXXXX")}"
mkdir -p "$OUT"
runs=0; bad=0; n=0
printf '%-24s %6s %-7s %4s %7s  %-36s %-5s %s\n' config moment signal exit stop "still running after 5 s" saved "ended during the stop"
for config in $CONFIGS; do
    sets=()
    case "$config" in kitti_composed|robot) sets=(--set player.loop=true) ;; esac
    for at in $MOMENTS; do
        # Sources without input (base station, replay) stop by themselves when idle: early only.
        case "$config" in base_station*|replay) [ "$at" -gt 3 ] && continue ;; esac
        sig="$SIG"; [ -z "$sig" ] && { [ $((n % 2)) = 0 ] && sig=TERM || sig=INT; }
        n=$((n + 1)); runs=$((runs + 1))
        dir="$OUT/${config}_${at}s"
        rm -rf "$dir"
        line="$(bash "$ROOT/tests/stop/stop_config.sh" "$config.yaml" "$at" --signal "$sig" --keep "$dir" "${sets[@]}" 2>&1)"
        rc=$?
        log="$dir/host.log"
        exit_status=$(sed -n 's/.* exit \([0-9]*\) .*/\1/p' <<< "$line" | head -n 1)
        stop_s=$(sed -n 's/.* stop *\([0-9.]*\) s .*/\1/p' <<< "$line" | head -n 1)
        waiting=$(grep -o "stopping: waiting for '[^']*' ([^)]*)" "$log" 2>/dev/null | head -n 1 | sed "s/stopping: waiting for //")
        saved=$(grep -c "\] saved " "$log" 2>/dev/null || true)
        # Work that ended between the signal and the end: the components' own lines.
        ended=$(awk '/\[host\] received SIG/ {on = 1; next} /\[host\] (saved|stopped)/ {on = 0}
                     on && /\[maintenance\] pass [0-9]+:/ {m++}
                     on && /\[mesh\].*meshed/ {me++}
                     on && /\[localisation\].*(relocalised|global)/ {g++}
                     on && /(map saved to|mesh written to)/ {s++}
                     END {o = ""; if (m) o = o m " maintenance pass "; if (me) o = o me " meshing ";
                          if (g) o = o g " global localisation "; if (s) o = o s " save"; print o}' "$log" 2>/dev/null)
        [ "$rc" = 0 ] || bad=$((bad + 1))
        printf '%-24s %5ss %-7s %4s %6ss  %-36s %-5s %s%s\n' "$config" "$at" "SIG$sig" "${exit_status:-?}" "${stop_s:-?}" \
            "${waiting:--}" "$saved" "${ended:--}" "$([ "$rc" = 0 ] || echo "  NOT CLEAN: $(grep -m1 '^  ' <<< "$line")")"
    done
done
echo "$runs runs, $((runs - bad)) clean; logs in $OUT"
[ "$bad" = 0 ]
