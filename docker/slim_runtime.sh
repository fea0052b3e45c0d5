#!/bin/sh
# The runtime stage's diet (docker/Dockerfile): after apt has installed runtime-packages.txt with
# every dependency Debian declares, purge the packages that no installed program loads. Debian's
# PCL I/O library depends on the whole of VTK 9.1, and VTK on Mesa, LLVM, ICU, MPI, PROJ and Tcl/Tk
# for rendering and I/O ltm never calls: about 280 MB of the 850 MB image. Kept: the packages of the
# base image and of every library in the ldd closure of /opt/ltm/bin/* and of the plugins loaded
# by name (Cyclone DDS's security plugins). dpkg then records those dependencies as unmet: an image
# built FROM this one that needs apt runs `apt-get -f install` first.
#   slim_runtime.sh BASE_PACKAGES   (the dpkg-query -W package names before the install)
set -eu
base="$1"
plugins="/usr/lib/x86_64-linux-gnu/libddsc0debian/*.so"
files="$(for f in /opt/ltm/bin/* $plugins; do echo "$f"; ldd "$f" | awk '/=> \// {print $3}'; done | sort -u)"
: > /tmp/needed
for f in $files; do
    case "$f" in /opt/ltm/*) continue ;; esac
    { dpkg -S "$f" 2>/dev/null || dpkg -S "$(readlink -f "$f")"; } | sed 's/:.*//' >> /tmp/needed
done
sort -u /tmp/needed "$base" > /tmp/keep
dpkg-query -W -f='${Package}\n' | sort > /tmp/installed
purge="$(comm -23 /tmp/installed /tmp/keep)"
size="$(dpkg-query -W -f='${Installed-Size}\n' $purge | awk '{ s += $1 } END { printf "%.0f", s / 1024 }')"
echo "slim_runtime: keeping $(comm -23 /tmp/keep "$base" | wc -l) packages the programs load, purging $(echo "$purge" | wc -w) (${size} MB):" $purge
# shellcheck disable=SC2086
dpkg --purge --force-depends $purge > /dev/null
rm -f /tmp/needed /tmp/keep /tmp/installed
