#!/bin/bash
# Builds the private armhf sysroot the 32-bit ARM Linux test build links against
# (toolchain/arm-linux-gnueabihf.cmake): Debian 12's armhf GoogleTest, libpng, zlib, libgpiod and
# libusb-1.0, downloaded with apt-get and unpacked with dpkg-deb -x into build/armhf-sysroot.
#
# Everything apt needs lives in build/armhf-apt (sources, package lists, cache, an empty dpkg
# status): the system's dpkg is never told about armhf (no `dpkg --add-architecture`, which would
# make the host's apt want armhf versions of everything), nothing is installed, and root is not
# needed. The C and C++ runtimes come from the cross toolchain (/usr/arm-linux-gnueabihf, packages
# libc6-dev-armhf-cross and libstdc++-12-dev-armhf-cross), not from here.
#
# Usage: scripts/armhf_sysroot.sh [SYSROOT]   (default build/armhf-sysroot; skips the work when
# the sysroot already holds this package list; delete the folder to refresh it)
set -euo pipefail
cd "$(dirname "$0")/.."
sysroot=$(realpath -m "${1:-build/armhf-sysroot}")
apt_dir=$(realpath -m "$(dirname "$sysroot")/armhf-apt")

# The -dev packages and the runtime packages their .so links point to. The tests link libpng and
# zlib statically (the toolchain file prefers .a), the runtime packages keep the .so links whole.
# libgpiod (1.6) and libusb-1.0 are for the Linux display backends (hal/linux, hal/usb); programs
# link them as shared libraries, and libudev1 is there because libusb-1.0.so needs it (at link
# time through -rpath-link, at run time in the emulated guest of scripts/ci_guest.sh).
pkgs=(libgtest-dev libpng-dev libpng16-16 zlib1g-dev zlib1g
      libgpiod-dev libgpiod2 libusb-1.0-0-dev libusb-1.0-0 libudev1)

stamp="$sysroot/.lr-sysroot"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "${pkgs[*]}" ]; then
  echo "armhf sysroot: up to date ($sysroot)"
  exit 0
fi

if ! command -v apt-get >/dev/null || ! command -v dpkg-deb >/dev/null; then
  echo "armhf sysroot: needs apt-get and dpkg-deb (Debian)" >&2
  exit 1
fi

# shellcheck source=scripts/armhf_apt.sh
source "$(dirname "${BASH_SOURCE[0]}")/armhf_apt.sh"
armhf_apt_setup "$apt_dir"
mkdir -p "$apt_dir/debs"

echo "armhf sysroot: apt-get update (private state in $apt_dir)"
apt-get "${apt_opts[@]}" -qq update
rm -f "$apt_dir"/debs/*.deb
(cd "$apt_dir/debs" && apt-get "${apt_opts[@]}" -qq download "${pkgs[@]}")

rm -rf "$sysroot"
mkdir -p "$sysroot"
for deb in "$apt_dir"/debs/*.deb; do
  echo "armhf sysroot: unpacking $(basename "$deb")"
  dpkg-deb -x "$deb" "$sysroot"
done
echo "${pkgs[*]}" >"$stamp"
echo "armhf sysroot: done ($sysroot)"
