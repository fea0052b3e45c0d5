#!/usr/bin/env bash
# The Debian 12 base image built offline: where no image registry is reachable but a Debian mirror
# is, debootstrap a minimal bookworm and import it as docker.io/library/debian:12 (the name the
# Dockerfile's FROM resolves to, so a build finds it locally and never pulls).
#   docker/make_base_image.sh [--mirror URL] [--engine podman|docker] [--tag NAME]
# Root only (debootstrap). About 150 MB, 2-5 min with a near mirror.
set -euo pipefail

mirror="${LTM_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
engine=""
tag="docker.io/library/debian:12"
while [ $# -gt 0 ]; do
    case "$1" in
        --mirror) mirror="${2:?--mirror needs a URL}"; shift 2 ;;
        --engine) engine="${2:?--engine needs podman or docker}"; shift 2 ;;
        --tag) tag="${2:?--tag needs a name}"; shift 2 ;;
        -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
        *) echo "make_base_image: unknown argument '$1' (--help)" >&2; exit 2 ;;
    esac
done
[ "$(id -u)" = 0 ] || { echo "make_base_image: debootstrap needs root" >&2; exit 1; }
command -v debootstrap >/dev/null || { echo "make_base_image: install debootstrap (apt-get install debootstrap)" >&2; exit 1; }
if [ -z "$engine" ]; then
    if command -v podman >/dev/null; then engine=podman
    elif command -v docker >/dev/null; then engine=docker
    else echo "make_base_image: neither podman nor docker is installed" >&2; exit 1; fi
fi

root="$(mktemp -d /var/tmp/ltm-bookworm.XXXXXX)"
trap 'rm -rf "$root"' EXIT
echo "make_base_image: debootstrap --variant=minbase bookworm from $mirror into $root" >&2
debootstrap --variant=minbase bookworm "$root" "$mirror" >&2
security="${mirror%/debian}/debian-security"
cat > "$root/etc/apt/sources.list" <<SOURCES
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb $security bookworm-security main
SOURCES
# As Debian's own images: no apt caches, no man pages and docs kept by later installs.
rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
mkdir -p "$root/etc/dpkg/dpkg.cfg.d"
cat > "$root/etc/dpkg/dpkg.cfg.d/ltm-slim" <<'DPKG'
path-exclude /usr/share/doc/*
path-include /usr/share/doc/*/copyright
path-exclude /usr/share/man/*
path-exclude /usr/share/info/*
path-exclude /usr/share/locale/*
DPKG
echo "make_base_image: importing as $tag ($engine)" >&2
tar -C "$root" --numeric-owner -c . |
    "$engine" import --change 'CMD ["/bin/bash"]' --change 'ENV LANG=C.UTF-8' - "$tag" >&2
"$engine" image inspect --format '{{.Size}}' "$tag" | awk -v t="$tag" '{ printf "make_base_image: %s, %.0f MB\n", t, $1 / 1e6 }'
