#!/usr/bin/env bash
# Independent reader test: @mcap/core (the official TypeScript MCAP library, from npm) reads the
# files ltm writes, and ltm reads files that @mcap/core writes. Exits 77 (ctest SKIP) when node,
# npm or the npm registry is not available.
#   independent_reader_test.sh LTM_MCAP NODE_DIR WORK_DIR [LTM_HOST KITTI_FOLDER]
set -u -o pipefail
LTM_MCAP=$1
NODE_DIR=$2   # npm packages are installed here once (cached in the build folder)
WORK=$3
LTM_HOST=${4:-}      # with these two, also a real DDS recording of a KITTI folder
KITTI=${5:-}
HERE=$(cd "${0%/*}" && pwd)
PACKAGES="@mcap/core@2.2.2 @mcap/nodejs@1.0.2 @foxglove/wasm-zstd@1.0.1 @foxglove/wasm-lz4@1.0.2"

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    echo "SKIP: node and npm are needed for the independent MCAP reader test"
    exit 77
fi
if [ "$(cat "$NODE_DIR/.installed" 2>/dev/null)" != "$PACKAGES" ]; then
    mkdir -p "$NODE_DIR"
    echo '{"name": "ltm-mcap-interop", "private": true}' > "$NODE_DIR/package.json"
    # shellcheck disable=SC2086
    if ! timeout 300 npm install --prefix "$NODE_DIR" --no-audit --no-fund --loglevel=error \
            $PACKAGES >"$NODE_DIR/npm.log" 2>&1; then
        echo "SKIP: npm could not install $PACKAGES (registry unreachable?): $(tail -n 1 "$NODE_DIR/npm.log")"
        exit 77
    fi
    echo "$PACKAGES" > "$NODE_DIR/.installed"
fi

rm -rf "$WORK"
mkdir -p "$WORK"
passed=0
failed=0
check() {  # check NAME COMMAND...
    local name=$1
    shift
    if "$@"; then
        passed=$((passed + 1))
    else
        echo "FAILED: $name"
        failed=$((failed + 1))
    fi
}
interop() { node "$HERE/mcap_interop.cjs" "$NODE_DIR" "$@"; }

# 1. @mcap/core reads ltm's files, every compression.
for c in zstd lz4 none; do
    "$LTM_MCAP" write-test-file "$WORK/ltm_$c.mcap" --manifest "$WORK/ltm_$c.json" --compression "$c" \
        || { echo "FAILED: ltm_mcap write-test-file $c"; exit 1; }
    check "@mcap/core reads ltm_$c.mcap" interop read "$WORK/ltm_$c.mcap" "$WORK/ltm_$c.json"
done

# 2. A recording cut short, recovered by ltm, read by @mcap/core as ltm reads the cut file.
size=$(stat -c %s "$WORK/ltm_zstd.mcap")
head -c $((size * 3 / 5)) "$WORK/ltm_zstd.mcap" > "$WORK/cut.mcap"
"$LTM_MCAP" manifest "$WORK/cut.mcap" -o "$WORK/cut.json" 2>/dev/null  # exit 1: it is cut
check "ltm recovers a cut file" "$LTM_MCAP" recover "$WORK/cut.mcap" -o "$WORK/recovered.mcap"
check "@mcap/core reads the recovered file" interop read "$WORK/recovered.mcap" "$WORK/cut.json"

# 3. ltm reads files that @mcap/core wrote.
for mode in zstd none unchunked; do
    f="$WORK/node_$mode.mcap"
    interop write "$f" "$WORK/node_$mode.json" "$mode" || { echo "FAILED: @mcap/core write $mode"; exit 1; }
    check "ltm verifies node_$mode.mcap" "$LTM_MCAP" verify "$f"
    check "ltm reads node_$mode.mcap" "$LTM_MCAP" manifest "$f" -o "$WORK/node_$mode.ltm.json"
    check "ltm reads node_$mode.mcap as written" interop compare "$WORK/node_$mode.json" "$WORK/node_$mode.ltm.json"
done

# 4. A real recording: ltm_host plays a KITTI folder and its recorder component writes the file.
if [ -n "$LTM_HOST" ]; then
    cat > "$WORK/record.yaml" <<YAML
domain_id: 171
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
namespace: /robot
topics: {points: stream, ground_truth: stream}
components:
  - name: player
    type: kitti_player
    params: {path: $KITTI, poses_file: $KITTI/poses_semantickitti.txt, mode: fast, wait_for_readers: 1}
  - name: recorder
    type: recorder
    params: {file: $WORK/dds_recording.mcap, all: true, compression: lz4}
YAML
    if "$LTM_HOST" "$WORK/record.yaml" --log-level warn; then
        check "ltm reads its DDS recording" "$LTM_MCAP" manifest "$WORK/dds_recording.mcap" -o "$WORK/dds_recording.json"
        check "@mcap/core reads ltm's DDS recording as ltm does" interop read "$WORK/dds_recording.mcap" "$WORK/dds_recording.json"
    else
        echo "FAILED: recording through ltm_host"
        failed=$((failed + 1))
    fi
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
