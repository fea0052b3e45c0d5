#!/usr/bin/env bash
# Runs one libFuzzer target of tests/fuzz (README.md). Called by `./ltm fuzz`.
#   fuzz.sh list                                  the targets
#   fuzz.sh TARGET [--seconds N] [-- LIBFUZZER_ARGS...]
# Builds build-fuzz (clang, AddressSanitizer + UndefinedBehaviorSanitizer, LTM_FUZZ=ON; installs
# clang and its fuzzer runtime when missing), then fuzzes TARGET for N seconds (default 60) on
# build-fuzz/corpus/TARGET, which starts as a copy of tests/fuzz/corpus/TARGET and keeps what
# libFuzzer finds. Crashes go to build-fuzz/crashes/TARGET/. Exit status 1 when one was found.
set -euo pipefail

# All in one function, so that bash has read the whole script before it runs (editing or
# updating the file during a run cannot change what the run does).
main() {
    FUZZ_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
    ROOT="$(cd "$FUZZ_DIR/../.." && pwd)"
    BUILD="${LTM_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
    JOBS="${LTM_JOBS:-$(nproc)}"

    die() { printf 'ltm fuzz: %s\n' "$*" >&2; exit 2; }
    say() { printf '\033[1mltm fuzz:\033[0m %s\n' "$*" >&2; }

    targets() {
        local f
        for f in "$FUZZ_DIR"/*_fuzz.cpp; do f="${f##*/}"; echo "${f%_fuzz.cpp}"; done
    }

    local usage="usage: ./ltm fuzz list | ./ltm fuzz TARGET [--seconds N] [-- LIBFUZZER_ARGS...]"

    [ $# -ge 1 ] || die "$usage"
    case "$1" in
        list) targets; exit 0 ;;
        -h|--help|help) echo "$usage"; exit 0 ;;
    esac
    TARGET="$1"; shift
    targets | grep -qx -- "$TARGET" ||
        die "unknown target '$TARGET' (known: $(targets | tr '\n' ' ' | sed 's/ $//'))"
    SECONDS_TO_RUN=60
    EXTRA=()
    while [ $# -gt 0 ]; do
        case "$1" in
            --seconds)
                [ $# -ge 2 ] || die "--seconds: needs a value"
                [[ "$2" =~ ^[0-9]+$ ]] && [ "$2" -gt 0 ] || die "--seconds: expected a positive integer, got '$2'"
                SECONDS_TO_RUN="$2"; shift 2 ;;
            --) shift; EXTRA=("$@"); break ;;
            *) die "unknown argument '$1'" ;;
        esac
    done

    # clang and its runtime libraries (libFuzzer, ASan, UBSan) from Debian.
    fuzzer_runtime() {
        command -v clang++ >/dev/null || return 1
        [ -f "$(clang++ -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a" ]
    }
    if ! fuzzer_runtime; then
        pkgs="clang libclang-rt-dev"
        say "installing $pkgs (clang with its fuzzer and sanitizer runtimes)"
        sudo=""
        if [ "$(id -u)" -ne 0 ]; then
            command -v sudo >/dev/null || die "not root and no sudo: install $pkgs first"
            sudo="sudo"
        fi
        $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q >/dev/null
        # shellcheck disable=SC2086
        $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $pkgs
        fuzzer_runtime || die "clang's libFuzzer runtime is still missing after installing $pkgs"
    fi

    if [ ! -f "$BUILD/build.ninja" ]; then
        say "configuring $BUILD (clang, LTM_FUZZ=ON)"
        CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
            -DLTM_FUZZ=ON >/dev/null
    fi
    BUILD_LOG="$BUILD/fuzz-build-$TARGET.log"
    say "building ltm_fuzz_$TARGET (log $BUILD_LOG)"
    # One build at a time in build-fuzz (two fuzz runs may start together).
    if ! flock "$BUILD/.build.lock" cmake --build "$BUILD" --target "ltm_fuzz_$TARGET" -- -j "$JOBS" \
            >"$BUILD_LOG" 2>&1; then
        grep -E 'error|FAILED' "$BUILD_LOG" | head -20 >&2
        die "building ltm_fuzz_$TARGET failed (log $BUILD_LOG)"
    fi

    CORPUS="$BUILD/corpus/$TARGET"
    CRASHES="$BUILD/crashes/$TARGET"
    mkdir -p "$CORPUS" "$CRASHES"
    cp -n "$FUZZ_DIR/corpus/$TARGET"/* "$CORPUS"/ 2>/dev/null || true
    DICT=()
    [ -f "$FUZZ_DIR/dict/$TARGET.dict" ] && DICT=("-dict=$FUZZ_DIR/dict/$TARGET.dict")
    LOG="$BUILD/fuzz-$TARGET.log"
    say "fuzzing $TARGET for ${SECONDS_TO_RUN}s on $CORPUS ($(ls "$CORPUS" | wc -l) inputs); log $LOG"

    export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:quarantine_size_mb=64}"
    export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
    before="$(ls "$CRASHES" | wc -l)"
    set +e
    "$BUILD/fuzz/ltm_fuzz_$TARGET" -max_total_time="$SECONDS_TO_RUN" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$CRASHES/" "${DICT[@]}" "${EXTRA[@]}" "$CORPUS" >"$LOG" 2>&1
    rc=$?
    set -e

    # Summary: executions, coverage and features, corpus size, crash files.
    execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$LOG" | tail -1)"
    last="$(grep -E '^#[0-9]+' "$LOG" | tail -1 || true)"
    cov="$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")"
    ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")"
    after="$(ls "$CRASHES" | wc -l)"
    echo "target: $TARGET  seconds: $SECONDS_TO_RUN  executions: ${execs:-?}  cov: ${cov:-?}  ft: ${ft:-?}  corpus: $(ls "$CORPUS" | wc -l) inputs"
    if [ "$after" -gt "$before" ] || [ "$rc" -ne 0 ]; then
        grep -E '^==[0-9]+==ERROR|^SUMMARY|runtime error|ltm fuzz finding|Test unit written' "$LOG" | head -20 || true
        ls -t "$CRASHES" | head -5 | sed "s|^|crash file: $CRASHES/|"
        echo "libFuzzer exit status $rc; full log: $LOG"
        exit 1
    fi
    echo "no crash"
}

main "$@"; exit $?  # on one line: nothing after it is read, even if the file changed
