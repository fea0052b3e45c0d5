#!/usr/bin/env bash
# ./ltm image: build and run the robot and base-station images with docker or podman
# (docker/README.md).
#   image base [--mirror URL]            the Debian 12 base image, offline (debootstrap + import)
#   image build [robot|base-station|all] [--jobs N] [--ccache DIR]
#   image run robot|base-station [--chroot] [--netns NS] [--results DIR] [--data DIR]
#             [--entrypoint PROGRAM] [-- LAUNCH.yaml HOST-ARGS... | PROGRAM-ARGS...]
# Engine: LTM_IMAGE_ENGINE=podman|docker, else podman if installed, else docker. Podman builds
# with --isolation=chroot. Where `podman run` is refused (this sandbox: crun cannot set
# RLIMIT_NOFILE/NPROC), `run --chroot` runs the image's entry point from its exported file
# system by chroot (root only).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
err() { printf 'ltm image: error: %s\n' "$*" >&2; exit 1; }
usage_err() { printf 'ltm image: error: %s (./ltm image help)\n' "$*" >&2; exit 2; }
say() { printf '\033[1mltm image:\033[0m %s\n' "$*" >&2; }

usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }

engine() {
    local e
    e="$(pick_engine)" || exit $?
    if [ "$e" = docker ] && ! docker info > /dev/null 2>&1; then
        err "docker cannot reach its daemon (docker info failed): start dockerd, or install podman"
    fi
    echo "$e"
}

pick_engine() {
    if [ -n "${LTM_IMAGE_ENGINE:-}" ]; then
        case "$LTM_IMAGE_ENGINE" in podman|docker) ;; *) usage_err "LTM_IMAGE_ENGINE is podman or docker, not '$LTM_IMAGE_ENGINE'" ;; esac
        command -v "$LTM_IMAGE_ENGINE" >/dev/null || err "$LTM_IMAGE_ENGINE is not installed"
        echo "$LTM_IMAGE_ENGINE"
    elif command -v podman >/dev/null; then echo podman
    elif command -v docker >/dev/null; then echo docker
    else err "neither podman nor docker is installed (Debian: apt-get install podman)"; fi
}

# The image name of a target.
image_of() {
    case "$1" in
        robot) echo localhost/ltm-robot ;;
        base-station) echo localhost/ltm-base-station ;;
        *) usage_err "the images are robot and base-station, not '$1'" ;;
    esac
}

build() {
    local targets=() jobs=1 ccache="" eng t start
    while [ $# -gt 0 ]; do
        case "$1" in
            robot|base-station) targets+=("$1"); shift ;;
            all) targets+=(base-station robot); shift ;;
            --jobs) [ $# -ge 2 ] || usage_err "--jobs needs a number"; jobs="$2"; shift 2 ;;
            --ccache) [ $# -ge 2 ] || usage_err "--ccache needs a folder"; ccache="$2"; shift 2 ;;
            *) usage_err "build: unknown argument '$1'" ;;
        esac
    done
    [ ${#targets[@]} -gt 0 ] || targets=(base-station robot)
    eng="$(engine)"
    local opts=(-f "$ROOT/docker/Dockerfile" --build-arg "JOBS=$jobs")
    if [ "$eng" = podman ]; then
        opts+=(--isolation=chroot)
        [ -z "$ccache" ] || opts+=(-v "$(realpath "$ccache"):/ccache")
    elif [ -n "$ccache" ]; then
        say "--ccache: docker build cannot mount a folder; building without it"
    fi
    for t in "${targets[@]}"; do
        start=$(date +%s)
        say "building $(image_of "$t") ($eng, stage $t, $jobs jobs)"
        "$eng" build "${opts[@]}" --target "$t" -t "$(image_of "$t")" "$ROOT"
        say "$(image_of "$t"): $(size_mb "$eng" "$(image_of "$t")") MB, built in $(($(date +%s) - start)) s"
    done
}

size_mb() { "$1" image inspect --format '{{.Size}}' "$2" | awk '{ printf "%.0f", $1 / 1e6 }'; }

run() {
    [ $# -ge 1 ] || usage_err "run: which image (robot or base-station)"
    local target="$1" chroot=0 netns="" results="$PWD/results/image-$1" data="" entry="" eng image
    shift
    image="$(image_of "$target")"
    local given=("$@")
    while [ $# -gt 0 ]; do
        case "$1" in
            --chroot) chroot=1; shift ;;
            --netns) [ $# -ge 2 ] || usage_err "--netns needs a network namespace"; netns="$2"; shift 2 ;;
            --results) [ $# -ge 2 ] || usage_err "--results needs a folder"; results="$2"; shift 2 ;;
            --data) [ $# -ge 2 ] || usage_err "--data needs a folder"; data="$(realpath "$2")"; shift 2 ;;
            --entrypoint) [ $# -ge 2 ] || usage_err "--entrypoint needs a program"; entry="$2"; shift 2 ;;
            --) shift; break ;;
            *) break ;;
        esac
    done
    mkdir -p "$results"
    results="$(realpath "$results")"
    eng="$(engine)"
    "$eng" image exists "$image" 2>/dev/null || "$eng" image inspect "$image" >/dev/null 2>&1 ||
        err "no image $image: ./ltm image build $target"
    if [ "$chroot" = 1 ]; then
        run_chroot "$eng" "$image" "$results" "$data" "$netns" "$entry" "$@"
        return
    fi
    local opts=(--rm --net=host -v "$results:/results")
    [ -z "$netns" ] || opts=(--rm "--net=ns:/run/netns/$netns" -v "$results:/results")
    [ -z "$data" ] || opts+=(-v "$data:/data:ro" -e LTM_DATA=/data)
    [ -z "$entry" ] || opts+=(--entrypoint "$entry")
    [ -t 0 ] && opts+=(-it)
    local log rc=0 tee_pid
    log="$(mktemp)"
    # stderr shown as it comes and kept, to tell a refused start from the host's own failure
    exec 3> >(tee "$log" >&2)
    tee_pid=$!
    "$eng" run "${opts[@]}" "$image" "$@" 2>&3 || rc=$?
    exec 3>&-
    wait "$tee_pid" 2>/dev/null || true
    if [ "$rc" != 0 ] && grep -q 'setrlimit\|cgroups in hybrid mode' "$log"; then
        rm -f "$log"
        say "$eng run was refused by the container runtime (crun cannot set the container's"
        say "resource limits or cgroups here): the image did not start. Run its entry point from"
        say "its exported file system by chroot instead (root):"
        say "  ./ltm image run $target --chroot ${given[*]}"
        exit "$rc"
    fi
    rm -f "$log"
    exit "$rc"
}

# The image's file system, exported once per image id into /var/tmp/ltm-image-<target>-<id>.
export_rootfs() {
    local eng="$1" image="$2" id dir cid
    id="$("$eng" image inspect --format '{{.Id}}' "$image")"
    dir="/var/tmp/ltm-image-${image##*/}-${id:0:12}"
    if [ ! -f "$dir/.exported" ]; then
        say "exporting $image (${id:0:12}) to $dir"
        rm -rf "$dir"
        mkdir -p "$dir"
        cid="$("$eng" create "$image")"
        "$eng" export "$cid" | tar -C "$dir" -x
        "$eng" rm "$cid" >/dev/null
        touch "$dir/.exported"
        # Earlier exports of this image name go, unless a run still has something mounted there
        # (its /results is the host's results folder: never delete through a mount).
        local old
        for old in "/var/tmp/ltm-image-${image##*/}-"*; do
            [ "$old" != "$dir" ] && [ -d "$old" ] || continue
            grep -qF " $old/" /proc/self/mounts || rm -rf "$old"
        done
    fi
    echo "$dir"
}

# Runs the image's entry point (its ENTRYPOINT, its CMD or the given arguments, its ENV and
# WORKDIR) in the exported file system by chroot, /results bound to the host's results folder.
# SIGINT/SIGTERM are forwarded to the host, which stops cleanly; the mounts are undone at exit.
run_chroot() {
    local eng="$1" image="$2" results="$3" data="$4" netns="$5" entrypoint="$6"
    shift 6
    [ "$(id -u)" = 0 ] || err "run --chroot needs root (chroot, mount)"
    local rootfs entry=() cmd=() envs=() workdir
    rootfs="$(export_rootfs "$eng" "$image")"
    mapfile -t entry < <("$eng" image inspect --format '{{range .Config.Entrypoint}}{{println .}}{{end}}' "$image" | sed '/^$/d')
    mapfile -t cmd < <("$eng" image inspect --format '{{range .Config.Cmd}}{{println .}}{{end}}' "$image" | sed '/^$/d')
    mapfile -t envs < <("$eng" image inspect --format '{{range .Config.Env}}{{println .}}{{end}}' "$image" | sed '/^$/d')
    workdir="$("$eng" image inspect --format '{{.Config.WorkingDir}}' "$image")"
    [ -z "$entrypoint" ] || { entry=("$entrypoint"); cmd=(); }
    [ $# -eq 0 ] || cmd=("$@")
    [ -z "$data" ] || envs+=(LTM_DATA=/data)
    local mounts=()
    mkdir -p "$rootfs/results" "$rootfs/proc" "$rootfs/dev" "$rootfs/sys" "$rootfs/tmp" "$rootfs/data"
    mount --bind "$results" "$rootfs/results" && mounts+=("$rootfs/results")
    mount -t proc proc "$rootfs/proc" && mounts+=("$rootfs/proc")
    mount --rbind /dev "$rootfs/dev" && mounts+=("$rootfs/dev")
    if [ -n "$data" ]; then mount --bind -o ro "$data" "$rootfs/data" && mounts+=("$rootfs/data"); fi
    cp /etc/resolv.conf /etc/hosts "$rootfs/etc/" 2>/dev/null || true
    # shellcheck disable=SC2064
    trap "undo_mounts ${mounts[*]}" EXIT
    local prefix=()
    [ -z "$netns" ] || prefix=(ip netns exec "$netns")
    say "running ${entry[*]} ${cmd[*]} from $image by chroot ($rootfs; /results: $results${netns:+; network namespace $netns})"
    local pid rc=0
    "${prefix[@]}" chroot "$rootfs" /usr/bin/env -i "${envs[@]}" /bin/sh -c 'cd "$0" && exec "$@"' \
        "${workdir:-/}" "${entry[@]}" "${cmd[@]}" &
    pid=$!
    # shellcheck disable=SC2064  # the pid now
    trap "kill -INT $pid 2>/dev/null || true" INT
    # shellcheck disable=SC2064
    trap "kill -TERM $pid 2>/dev/null || true" TERM
    while :; do
        rc=0
        wait "$pid" || rc=$?
        kill -0 "$pid" 2>/dev/null || break
    done
    trap - INT TERM
    return "$rc"
}

undo_mounts() {
    local m i
    local all=("$@")
    for ((i = ${#all[@]} - 1; i >= 0; --i)); do
        m="${all[i]}"
        umount -R "$m" 2>/dev/null || umount -l "$m" 2>/dev/null || true
    done
}

CMD="${1:-help}"
[ $# -gt 0 ] && shift
case "$CMD" in
    base) exec "$ROOT/docker/make_base_image.sh" "$@" ;;
    build) build "$@" ;;
    run) run "$@" ;;
    help|-h|--help) usage ;;
    *) usage_err "unknown command '$CMD'" ;;
esac
