#!/usr/bin/env bash
# ./ltm bench budget [--config C] [--scenario S] [--sensor M] [--frames A:B] [--out D] [--no-perf]
# The robot's mission through the host at the sensor's real rate: a kitti_player plays a
# scenario's scans (rendered once by ltm_sim, so rendering is not counted) at their own times
# (10 Hz) into the launch config, while `ltm_budget monitor` samples each host's threads from
# /proc (every 0.1 s), a probe component records every scan's, pose's and map update's source
# timestamp, and perf samples the robot's host. `ltm_budget report` then prints, per component and
# thread: CPU a scan, share of one core (average, worst 1 s window), peak and final memory, scans
# the odometry missed and the localisation skipped, latency scan -> pose and scan -> map update,
# against the targets of issue 28; memory over time as D/<run>/memory.svg.
#   --config lifelong            robot_lifelong.yaml on a fresh site (day 0: session 0 of the
#                                scenario) and a second day on it (session 1)
#   --config base_station        robot.yaml (session 0) and base_station.yaml, two hosts
#   --config base_station_multi  two robot.yaml hosts (/robot1: session 0, /robot2: session 1)
#                                and base_station_multi.yaml
#   --config all                 the three in turn (default)
#   --sensor M                   render the scans with the simulator's sensor M (os1_64, hdl64e,
#                                vlp32c, vlp16) instead of the scenario's; every component's
#                                sensor preset follows the scans (`ltm_budget sensor`), and the
#                                robot's CPU target is 50 % of a core (100 % with 64 beams)
#   --site-from S                lifelong: day 1 only, on a copy of the site S (a site folder with
#                                day 0's version, e.g. an earlier run's D/lifelong/site): an
#                                after-change day 1 without playing day 0 again
#   --day0-only                  lifelong: day 0 only (e.g. with --frames: a 64-beam sensor's
#                                scans are 2-3x a VLP-32C's on disk)
#   --set NAME.KEY=VALUE         lifelong: passed on to the robot's host (repeatable; e.g. a
#                                before/after of one setting with the same build)
#   --report-only                the reports again from D's samples and probes (no host runs)
#   --maintenance-share X        the maintenance worker's CPU at most X of one core (its
#                                cpu_share: passes spread, not bursts; 1: unpaced; default: the
#                                launch config's), with --background-share 0 (then default 0.35)
#   --background-share X         lifelong: the background work (maintenance worker, the mapping's
#                                clearing of a pass's cells and its periodic saves) together at
#                                most X of one core, one budget (cpu_budget: background; the
#                                localisation's global queries charged to it too); default: the
#                                launch config's (robot_lifelong.yaml: 0.4, robot.yaml: the
#                                maintenance 0.35); 0: each its own (maintenance
#                                --maintenance-share, clearing 0.15, saves unpaced: before issue
#                                28's budget-peaks)
#   --nice N                     the hosts at nice N (e.g. -5, root: the mission ahead of the
#                                machine's other work, as on a robot's own computer; said in the
#                                report)
# Every host on domain LTM_BENCH_DOMAIN (default 66). The machine's load is measured and printed
# with each run: CPU figures are CPU time (load does not inflate them); latencies are wall clock
# and are labelled with the load they were measured under.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
DOMAIN="${LTM_BENCH_DOMAIN:-66}"
CONFIG=all; SCENARIO="$ROOT/components/simulator/scenarios/site_loop.yaml"; FRAMES=""; OUT=""; PERF=1
REPORT_ONLY=0; NICE=""; MAINT_SHARE=""; BACKGROUND_SHARE=""; SENSOR=""; SITE_FROM=""; DAY0_ONLY=0; EXTRA_SETS=()

usage() {
    echo "The robot's mission at the sensor's rate: CPU, memory, missed scans, latency per component"
    printf 'Usage: ./ltm bench budget [OPTIONS]\n\nOptions:\n'
    printf '  %-22s%s\n' "-h,--help" "Print this help message and exit" \
        "--config C" "lifelong, base_station, base_station_multi or all (default)" \
        "--scenario S" "the scenario (default site_loop); sessions 0 and 1 are played" \
        "--sensor M" "the simulator's sensor for the scans (os1_64, hdl64e, vlp32c, vlp16; default: the scenario's)" \
        "--frames A:B" "only scans A..B-1 of each session (a short run)" \
        "--out D" "the results (default results/budget-<time>)" \
        "--no-perf" "no perf profile of the robot's host" \
        "--site-from S" "lifelong: day 1 only, on a copy of site S (day 0's version)" \
        "--day0-only" "lifelong: day 0 only" \
        "--set NAME.KEY=VALUE" "lifelong: a parameter of the robot's host (repeatable)" \
        "--report-only" "write the reports again from D's samples and probes (needs --out D)" \
        "--nice N" "run the hosts at nice N (negative: ahead of the machine's other work; root)" \
        "--maintenance-share X" "the maintenance worker's CPU share of a core (default: the launch config's; 1: unpaced), with --background-share 0" \
        "--background-share X" "lifelong: maintenance + the mapping's clearing and saves together at most X of a core (default: the launch config's, 0.4; 0: each its own)"
}
fail() { echo "ltm bench budget: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --no-perf) PERF=0; shift ;;
        --report-only) REPORT_ONLY=1; shift ;;
        --day0-only) DAY0_ONLY=1; shift ;;
        --set) [ $# -ge 2 ] || fail "--set: needs NAME.KEY=VALUE"; EXTRA_SETS+=(--set "$2"); shift 2 ;;
        --config|--scenario|--sensor|--frames|--out|--nice|--maintenance-share|--site-from|--background-share)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --config) CONFIG="$2" ;; --scenario) SCENARIO="$2" ;;
                --frames) FRAMES="$2" ;; --out) OUT="$2" ;; --nice) NICE="$2" ;;
                --maintenance-share) MAINT_SHARE="$2" ;; --sensor) SENSOR="$2" ;;
                --site-from) SITE_FROM="$2" ;; --background-share) BACKGROUND_SHARE="$2" ;;
            esac
            shift 2 ;;
        *) fail "unknown argument '$1' (--help)" ;;
    esac
done
case "$CONFIG" in lifelong|base_station|base_station_multi|all) ;; *) fail "--config: lifelong, base_station, base_station_multi or all, got '$CONFIG'" ;; esac
[ -f "$SCENARIO" ] || fail "--scenario: no such file: $SCENARIO"
SCENARIO="$(cd "$(dirname "$SCENARIO")" && pwd)/$(basename "$SCENARIO")"
[ -z "$FRAMES" ] || [[ "$FRAMES" =~ ^[0-9]*:[0-9]*$ ]] || fail "--frames: A:B, got '$FRAMES'"
[ -z "$NICE" ] || [[ "$NICE" =~ ^-?[0-9]+$ ]] || fail "--nice: a whole number, got '$NICE'"
[ -z "$SENSOR" ] || [[ "$SENSOR" =~ ^[a-z0-9_]+$ ]] || fail "--sensor: a simulator model (os1_64, hdl64e, vlp32c, vlp16), got '$SENSOR'"
[ -z "$SITE_FROM" ] || [ "$DAY0_ONLY" = 0 ] || fail "--site-from and --day0-only: one or the other"
[ -z "$SITE_FROM" ] || [ -d "$SITE_FROM/versions" ] || fail "--site-from: $SITE_FROM is not a site (no versions/ in it)"
[ -z "$MAINT_SHARE" ] || [[ "$MAINT_SHARE" =~ ^[0-9]*\.?[0-9]+$ ]] || fail "--maintenance-share: a number in (0, 1], got '$MAINT_SHARE'"
[ -z "$BACKGROUND_SHARE" ] || [[ "$BACKGROUND_SHARE" =~ ^[0-9]*\.?[0-9]+$ ]] || fail "--background-share: a number in [0, 1] (0: each its own), got '$BACKGROUND_SHARE'"
for exe in ltm_host ltm_sim ltm_budget; do
    [ -x "$BIN/$exe" ] || fail "$BIN/$exe is not built (ninja -C build ltm_host ltm_sim ltm_budget)"
done
if [ "$PERF" = 1 ] && ! command -v perf >/dev/null; then
    echo "ltm bench budget: perf is missing (apt-get install linux-perf): no profile" >&2; PERF=0
fi
[ "$REPORT_ONLY" = 0 ] || [ -n "$OUT" ] || fail "--report-only: needs --out D (a run's folder)"
OUT="${OUT:-$ROOT/results/budget-$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$OUT" || fail "--out: cannot create $OUT"
OUT="$(cd "$OUT" && pwd)"
NAME="$(basename "$SCENARIO" .yaml)"
echo "ltm bench budget: $CONFIG on $NAME${SENSOR:+ with a $SENSOR}, domain $DOMAIN, results in $OUT"

# scans N: the folder of session N's scans (rendered once, kept beside the results).
scans() {
    local dir="$ROOT/results/budget-scans/$NAME${SENSOR:+-$SENSOR}-s$1${FRAMES:+-${FRAMES/:/-}}"
    if [ ! -f "$dir/times.txt" ]; then
        echo "  rendering $NAME session $1 ${SENSOR:+with a $SENSOR }${FRAMES:+(frames $FRAMES) }into $dir" >&2
        "$BIN/ltm_sim" "$SCENARIO" --session "$1" ${FRAMES:+--frames "$FRAMES"} \
            ${SENSOR:+--sensor "$SENSOR"} --quiet \
            --out "$dir.tmp" >&2 || fail "ltm_sim failed for session $1"
        rm -rf "$dir"; mv "$dir.tmp" "$dir"
    fi
    echo "$dir"
}

# The machine: load average and the share of both cores busy (everyone's) since `cpu_mark`.
cpu_mark() { awk '/^cpu /{print $2+$3+$4+$7+$8, $2+$3+$4+$5+$6+$7+$8}' /proc/stat; }
load_note() {  # load_note "BUSY0 TOTAL0"
    local now busy
    now="$(cpu_mark)"
    busy=$(awk -v a="$1" -v b="$now" 'BEGIN{split(a,x," ");split(b,y," ");
        if (y[2]>x[2]) printf "%.0f", 100*(y[1]-x[1])/(y[2]-x[2]); else print "?"}')
    echo "machine during the run: $(nproc) cores ${busy} % busy (all users), load average $(cut -d' ' -f1-3 /proc/loadavg) at the end (latencies are wall clock under this load)${NICE:+; the hosts ran at nice $NICE}"
}

# start_host LABEL DIR LAUNCH [ENV=V ...] -- [HOST ARGS]: starts a host in the background with its
# monitor; sets PIDS[LABEL] and MONS[LABEL].
declare -A PIDS MONS
start_host() {
    local label="$1" dir="$2" launch="$3"; shift 3
    local -a envs=()
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do envs+=("$1"); shift; done
    shift
    mkdir -p "$dir"
    local -a nice=()
    [ -z "$NICE" ] || nice=(nice -n "$NICE")
    env "${envs[@]}" LTM_OUT="$dir" "${nice[@]}" "$BIN/ltm_host" "$launch" --set "domain_id=$DOMAIN" "$@" \
        > "$dir/host.log" 2>&1 &
    PIDS[$label]=$!
    "$BIN/ltm_budget" monitor --pid "${PIDS[$label]}" --out "$dir/samples.txt" 2>>"$dir/monitor.log" &
    MONS[$label]=$!
}
# profile LABEL DIR: perf on the host (199 Hz: about 1 % of a core) until it exits.
profile() {
    [ "$PERF" = 1 ] || return 0
    # After the start-up: perf follows the threads that exist when it attaches (a host that had
    # not made its components' threads yet was profiled on its main thread alone).
    (sleep 5; exec perf record -F 199 -g -p "${PIDS[$1]}" -o "$2/perf.data") > "$2/perf.log" 2>&1 &
    PERFS+=($!)
}
PERFS=()
wait_hosts() {  # waits for every host, monitor and profile; prints a host that failed
    local label rc
    for label in "${!PIDS[@]}"; do
        rc=0; wait "${PIDS[$label]}" || rc=$?
        [ "$rc" = 0 ] || echo "  host $label exited with $rc (see its host.log)"
        wait "${MONS[$label]}" 2>/dev/null
    done
    local p; for p in "${PERFS[@]}"; do wait "$p" 2>/dev/null; done
    PIDS=(); MONS=(); PERFS=()
}
perf_summary() {  # DIR: where the robot host's CPU went (self time, by thread and function)
    [ -f "$1/perf.data" ] || return 0
    perf report -i "$1/perf.data" --no-children --sort comm,sym --stdio 2>/dev/null |
        grep -E '^ +[0-9.]+%' | head -40 > "$1/perf_top.txt"
    perf report -i "$1/perf.data" --no-children --sort comm --stdio 2>/dev/null |
        grep -E '^ +[0-9.]+%' | head -20 > "$1/perf_threads.txt"
    {
        echo; echo "## perf (199 Hz, self time) of the robot's host: threads"; echo
        echo '```'; cat "$1/perf_threads.txt"; echo '```'
        echo; echo "hottest functions (thread, function: share of all samples)"; echo
        echo '```'; head -30 "$1/perf_top.txt"; echo '```'
    } >> "$1/report.md"
    echo "  perf: $1/perf_top.txt (report: perf report -i $1/perf.data)"
}
# sensor_note DIR SCANS: the scans' preset, sensor and beams (ltm_budget sensor) into DIR/sensor.txt.
sensor_note() { "$BIN/ltm_budget" sensor --scans "$2" > "$1/sensor.txt" || fail "ltm_budget sensor: $2"; }
sensor_name() { cut -f2 "$1/sensor.txt" 2>/dev/null || echo "?"; }
sensor_preset() { cut -f1 "$1/sensor.txt"; }
# The robot's CPU target (issue 28): half a core on a VLP-32C, a whole core on a 64-beam sensor.
target_share() { if [ "$(cut -f3 "$1/sensor.txt" 2>/dev/null || echo 0)" -ge 64 ]; then echo 1.0; else echo 0.5; fi; }
published() { grep -oE 'published [0-9]+ scans' "$1" | tail -1 | grep -oE '[0-9]+' || echo 0; }

# What the components said of themselves at the end (host.log): the localisation's scans
# localised, relocalisations and skipped while busy; the maintenance's passes.
component_lines() {
    { echo; echo "## the components' own counts (host.log)"; echo; echo '```'
      grep -E '\[maintenance\] pass [0-9]+:' "$1" | sed -E 's/^[0-9:.]+ +[a-z]+ +//' | tail -6
      grep -E '\[(localisation|maintenance|odometry)\] [0-9]+ scans' "$1" | sed -E 's/^[0-9:.]+ +[a-z]+ +//'
      echo '```'; } >> "$2"
}

# shutdown_at HOSTLOG SAMPLES: the wall-clock time (epoch seconds) the host began its shutdown
# (every source finished), its log's local time of day on the samples' first day; nothing if it
# did not say so.
shutdown_at() {
    local hms first day t
    hms="$(grep -m1 -E '\[host\] every source finished' "$1" | cut -d' ' -f1)"
    first="$(awk '$1=="s"{print int($2); exit}' "$2" 2>/dev/null)"
    [ -n "$hms" ] && [ -n "$first" ] || return 0
    day="$(date -d "@$first" +%F)" || return 0
    t="$(date -d "$day $hms" +%s.%N 2>/dev/null)" || return 0
    # (a run over midnight: the shutdown is on the next day)
    awk -v t="$t" -v f="$first" 'BEGIN{ if (t + 0 < f + 0) t += 86400; printf "%.3f\n", t }'
}

report_lifelong_day() {  # DAY SESSION
    local day="$1" dir="$OUT/lifelong/day$1"
    [ -f "$dir/samples.txt" ] || { echo "  no $dir/samples.txt: day $day did not run"; return; }
    local stop; stop="$(shutdown_at "$dir/host.log" "$dir/samples.txt")"
    "$BIN/ltm_budget" report --host "robot:$dir/samples.txt:$dir/launch.yaml" --probe "$dir/probe.csv" \
        --published "$(published "$dir/host.log")" --out "$dir" --with-pose \
        --target-share "$(target_share "$dir")" \
        ${stop:+--mission-end "$stop"} \
        --title "robot_lifelong.yaml, $NAME session $2 (day $day), $(sensor_name "$dir") at 10 Hz" \
        --note "$(cat "$dir/load.txt" 2>/dev/null)" > /dev/null || echo "  report failed: see above"
    component_lines "$dir/host.log" "$dir/report.md"
    python3 "$ROOT/components/bench/budget/global_during.py" "$dir/host.log" "$dir/probe.csv" \
        >> "$dir/report.md" || echo "  global_during.py failed: see above"
    perf_summary "$dir"
    echo "  report: $dir/report.md"
}

run_lifelong_day() {  # DAY SESSION
    local day="$1" dir="$OUT/lifelong/day$1" s mark
    s="$(scans "$2")" || exit 2
    mkdir -p "$dir"
    sensor_note "$dir" "$s"
    "$BIN/ltm_budget" variant --in "$ROOT/launch_configs/robot_lifelong.yaml" --out "$dir/launch.yaml" \
        --replace sensor --scans "$s" --presets-of "$s" --wait-for-readers 4 --probe "$dir/probe.csv" \
        --probe-inputs points odometry pose map_changes || exit 2
    echo "  lifelong day $day: $(wc -l < "$s/times.txt") scans of session $2 ($(sensor_name "$dir"), preset $(sensor_preset "$dir")) at 10 Hz (about $(( $(wc -l < "$s/times.txt") / 600 + 1 )) min)"
    mark="$(cpu_mark)"
    # Live: a scan that comes while the localiser is busy replaces the waiting one (counted), and
    # its global queries run on their own thread (global_thread, the default when live); the
    # maintenance worker paced to a share of a core (cpu_share); with --background-share (the
    # default) it, the mapping's clearing and the mapping's periodic saves draw from one budget.
    # Neither given: the launch config's own pacing (robot_lifelong.yaml: one budget of 0.4),
    # as a user runs it.
    local pace=()
    if [ "$BACKGROUND_SHARE" = 0 ]; then  # each its own: no shared budget
        pace=(--set "maintenance.cpu_share=${MAINT_SHARE:-0.35}" --set 'maintenance.cpu_budget=""'
              --set mapping.map_changes_cpu_share=0.15 --set 'mapping.cpu_budget=""')
    elif [ -n "$BACKGROUND_SHARE" ]; then
        pace=(--set "maintenance.cpu_share=$BACKGROUND_SHARE" --set maintenance.cpu_budget=background
              --set "mapping.map_changes_cpu_share=$BACKGROUND_SHARE" --set mapping.cpu_budget=background)
    elif [ -n "$MAINT_SHARE" ]; then
        pace=(--set "maintenance.cpu_share=$MAINT_SHARE")
    fi
    # Live: the localisation skips while busy, its global queries on their own thread charged to
    # the background budget (robot_lifelong.yaml's, offline: in-line).
    local live=(--set localisation.skip_while_busy=true)
    [ "$BACKGROUND_SHARE" = 0 ] || live+=(--set localisation.global_cpu_budget=background)
    start_host robot "$dir" "$dir/launch.yaml" LTM_SITE="$OUT/lifelong/site" -- \
        "${live[@]}" "${pace[@]}" "${EXTRA_SETS[@]}"
    profile robot "$dir"
    wait_hosts
    load_note "$mark" > "$dir/load.txt"
    report_lifelong_day "$@"
}

base_dir() { if [ "$1" = 1 ]; then echo "$OUT/base_station"; else echo "$OUT/base_station_multi"; fi; }
base_yaml() { if [ "$1" = 1 ]; then echo base_station.yaml; else echo base_station_multi.yaml; fi; }

report_base_station() {  # ROBOTS
    local n="$1" dir base i h stop
    dir="$(base_dir "$n")"; base="$(base_yaml "$n")"
    for ((i = 1; i <= n; ++i)); do
        h="robot$i"
        [ -f "$dir/$h/samples.txt" ] || { echo "  no $dir/$h/samples.txt: did not run"; continue; }
        stop="$(shutdown_at "$dir/$h/host.log" "$dir/$h/samples.txt")"
        "$BIN/ltm_budget" report --host "$h:$dir/$h/samples.txt:$dir/$h/launch.yaml" \
            --host "base:$dir/base/samples.txt:$ROOT/launch_configs/$base" --probe "$dir/$h/probe.csv" \
            --published "$(published "$dir/$h/host.log")" --out "$dir/$h" \
            --target-share "$(target_share "$dir/$h")" ${stop:+--mission-end "$stop"} \
            --title "$base with $n robot(s): $h's host and the base station's, $(sensor_name "$dir/$h") at 10 Hz" \
            --note "$(cat "$dir/load.txt" 2>/dev/null)" > /dev/null || echo "  report failed: see above"
        component_lines "$dir/$h/host.log" "$dir/$h/report.md"
        [ "$i" = 1 ] && perf_summary "$dir/robot1"
        echo "  report: $dir/$h/report.md"
    done
}

run_base_station() {  # ROBOTS (1 or 2)
    local n="$1" dir base mark i s
    dir="$(base_dir "$n")"; base="$(base_yaml "$n")"
    mkdir -p "$dir"
    # Every robot's scans rendered first: the base station stops idle_exit_s (10 s) after its
    # robots' data stops, and it started before a robot that was still rendering got none at all.
    for ((i = 1; i <= n; ++i)); do scans $((i - 1)) > /dev/null || exit 2; done
    mark="$(cpu_mark)"
    # Every preset follows the scans' sensor (the robots' variants, the base station's mapping).
    s="$(scans 0)" || exit 2
    mkdir -p "$dir/base"; sensor_note "$dir/base" "$s"
    # Each host its own site folder, new (robot.yaml's and the base station's default,
    # results/site under the working directory, was one folder for all the hosts of a run and
    # stayed there for the next run: a robot started on an earlier run's version).
    rm -rf "$dir/base/site"
    start_host base "$dir/base" "$ROOT/launch_configs/$base" LTM_SITE="$dir/base/site" -- \
        --set "mapping.preset=$(sensor_preset "$dir/base")"
    for ((i = 1; i <= n; ++i)); do
        s="$(scans $((i - 1)))" || exit 2
        mkdir -p "$dir/robot$i"
        sensor_note "$dir/robot$i" "$s"
        "$BIN/ltm_budget" variant --in "$ROOT/launch_configs/robot.yaml" --out "$dir/robot$i/launch.yaml" \
            --presets-of "$s" --probe "$dir/robot$i/probe.csv" --probe-inputs points odometry || exit 2
        local ns=/robot; [ "$n" = 1 ] || ns=/robot$i
        echo "  robot$i ($ns): $(wc -l < "$s/times.txt") scans of session $((i - 1)) at 10 Hz"
        rm -rf "$dir/robot$i/site"
        start_host "robot$i" "$dir/robot$i" "$dir/robot$i/launch.yaml" LTM_DATA="$s" \
            LTM_SITE="$dir/robot$i/site" -- \
            --set namespace=$ns
        [ "$i" = 1 ] && profile robot1 "$dir/robot$i"
    done
    wait_hosts
    load_note "$mark" > "$dir/load.txt"
    report_base_station "$n"
}

if [ "$REPORT_ONLY" = 1 ]; then
    if [ "$CONFIG" = lifelong ] || [ "$CONFIG" = all ]; then report_lifelong_day 0 0; report_lifelong_day 1 1; fi
    if [ "$CONFIG" = base_station ] || [ "$CONFIG" = all ]; then report_base_station 1; fi
    if [ "$CONFIG" = base_station_multi ] || [ "$CONFIG" = all ]; then report_base_station 2; fi
else
    if [ "$CONFIG" = lifelong ] || [ "$CONFIG" = all ]; then
        rm -rf "$OUT/lifelong/site"   # a fresh site: day 0 maps it
        if [ -n "$SITE_FROM" ]; then   # or day 0's site as given: day 1 only
            mkdir -p "$OUT/lifelong" && cp -a "$SITE_FROM" "$OUT/lifelong/site" ||
                fail "--site-from: cannot copy $SITE_FROM"
            echo "  lifelong: day 1 on a copy of $SITE_FROM"
        else
            run_lifelong_day 0 0
        fi
        [ "$DAY0_ONLY" = 1 ] || run_lifelong_day 1 1
    fi
    if [ "$CONFIG" = base_station ] || [ "$CONFIG" = all ]; then run_base_station 1; fi
    if [ "$CONFIG" = base_station_multi ] || [ "$CONFIG" = all ]; then run_base_station 2; fi
fi
echo "ltm bench budget: done; reports: $(find "$OUT" -name report.md | sort | tr '\n' ' ')"
