#!/usr/bin/env bash
# VDBFusion as a side-by-side peer of ltm's dense mesh: builds VDBFusion's C++ core from a snapshot
# of its public repository (github.com/PRBonn/vdbfusion) together with ltm's runner
# (vdbfusion_runner.cpp, CMakeLists.txt beside this script) in a build folder OUTSIDE the
# repository, then runs the runner on a scan folder. Nothing of VDBFusion is part of ltm.
#
#   vdbfusion.sh [--source DIR] [--build-dir DIR] build
#   vdbfusion.sh [--source DIR] [--build-dir DIR] path     # build, print the runner
#   vdbfusion.sh [--source DIR] commit                     # the source snapshot's commit
#   vdbfusion.sh [--source DIR] [--build-dir DIR] SCAN_DIR [RUNNER ARGS]
#                                  (vdbfusion.sh --help-runner: the runner's own options)
#
# Where things are (options win over the environment, which wins over the defaults):
#   VDBFusion source  --source, VDBFUSION_SOURCE     default /tmp/peer/vdbfusion-src
#   build folder      --build-dir, VDBFUSION_BUILD   default /tmp/ltm-peers/vdbfusion-build
# A missing source folder is unpacked from a bare git mirror when there is one (VDBFUSION_GIT,
# default .mirror/PRBonn+vdbfusion/repo next to the checkout, its HEAD); otherwise put a
# checkout there (git clone https://github.com/PRBonn/vdbfusion DIR) or give --source.
# Debian packages the build needs: cmake ninja-build g++ libeigen3-dev libopenvdb-dev libtbb-dev
# (ltm's own mesh needs the same); missing ones are installed with apt-get (as root or with sudo).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="$(dirname "$(cd "$HERE/../../../.." && pwd)")"  # the folder that holds the checkout
SOURCE="${VDBFUSION_SOURCE:-/tmp/peer/vdbfusion-src}"
BUILD="${VDBFUSION_BUILD:-/tmp/ltm-peers/vdbfusion-build}"
GIT_DIR_MIRROR="${VDBFUSION_GIT:-$OUT/.mirror/PRBonn+vdbfusion/repo}"
PACKAGES=(cmake ninja-build g++ libeigen3-dev libopenvdb-dev libtbb-dev)

say() { printf 'vdbfusion.sh: %s\n' "$*" >&2; }
die() { printf 'vdbfusion.sh: error: %s\n' "$*" >&2; exit 1; }

while [ $# -gt 0 ]; do
    case "$1" in
        --source|--build-dir)
            [ $# -ge 2 ] || die "$1 needs a folder"
            case "$1" in
                --source) SOURCE="$2" ;;
                --build-dir) BUILD="$2" ;;
            esac
            shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) break ;;
    esac
done
[ $# -ge 1 ] || die "usage: vdbfusion.sh [--source DIR] [--build-dir DIR] build|path|SCAN_DIR [ARGS] (--help)"

install_packages() {
    local missing=() p
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    say "the VDBFusion peer build needs Debian packages that are missing: ${missing[*]}; installing them"
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || die "not root and no sudo: install ${missing[*]} first"
        sudo="sudo"
    fi
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q >/dev/null
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
}

# The source tree: as given, else unpacked from the mirror (its commit in SNAPSHOT_COMMIT).
sources() {
    [ -f "$SOURCE/src/vdbfusion/vdbfusion/VDBVolume.cpp" ] && return 0
    [ -d "$GIT_DIR_MIRROR" ] || die "no VDBFusion source in $SOURCE (no src/vdbfusion/vdbfusion/VDBVolume.cpp) and no mirror $GIT_DIR_MIRROR: put a snapshot of github.com/PRBonn/vdbfusion there (git clone https://github.com/PRBonn/vdbfusion $SOURCE) or set VDBFUSION_SOURCE"
    local commit
    commit="$(git --git-dir="$GIT_DIR_MIRROR" rev-parse 'HEAD^{commit}')" || die "$GIT_DIR_MIRROR: no HEAD"
    say "unpacking $GIT_DIR_MIRROR at $commit into $SOURCE"
    mkdir -p "$SOURCE"
    git --git-dir="$GIT_DIR_MIRROR" archive "$commit" | tar -x -C "$SOURCE"
    echo "$commit" > "$SOURCE/SNAPSHOT_COMMIT"
}

# build: configure once, then an incremental build (quiet unless it fails).
build() {
    sources
    install_packages
    local log="$BUILD/build.log"
    mkdir -p "$BUILD"
    if [ ! -f "$BUILD/build.ninja" ] ||
        ! grep -qxF "VDBFUSION_SOURCE:PATH=$SOURCE" "$BUILD/CMakeCache.txt" 2>/dev/null; then
        say "configuring VDBFusion ($SOURCE) and the runner in $BUILD (Release)"
        cmake -S "$HERE" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DVDBFUSION_SOURCE="$SOURCE" > "$log" 2>&1 \
            || { cat "$log" >&2; die "configuring failed (log above, $log)"; }
    fi
    cmake --build "$BUILD" --target vdbfusion_runner -- -j "${LTM_JOBS:-$(nproc)}" > "$log" 2>&1 \
        || { cat "$log" >&2; die "building failed (log above, $log)"; }
    [ -x "$BUILD/vdbfusion_runner" ] || die "no runner in $BUILD after the build"
}

# The snapshot's commit: SNAPSHOT_COMMIT, or git, or "unknown".
source_commit() {
    cat "$SOURCE/SNAPSHOT_COMMIT" 2>/dev/null || git -C "$SOURCE" rev-parse HEAD 2>/dev/null || echo unknown
}

case "$1" in
    build) build; say "built $BUILD/vdbfusion_runner from VDBFusion $SOURCE (commit $(source_commit))" ;;
    path) build; echo "$BUILD/vdbfusion_runner" ;;
    commit) source_commit ;;
    --help-runner) build; exec "$BUILD/vdbfusion_runner" --help ;;
    -*) die "unknown option '$1' (--help)" ;;
    *) build; exec "$BUILD/vdbfusion_runner" "$@" ;;
esac
