#!/bin/bash
# Builds the private sysroot an ARM Linux cross build links against: Debian 12's GoogleTest,
# libpng, zlib, libgpiod and libusb-1.0 for one architecture, downloaded with apt-get and
# unpacked with dpkg-deb -x into build/ARCH-sysroot:
#   armhf (the default): the 32-bit build, toolchain/arm-linux-gnueabihf.cmake;
#   arm64: the 64-bit build, toolchain/aarch64-linux-gnu.cmake.
#
# Everything apt needs lives in build/ARCH-apt (sources, package lists, cache, an empty dpkg
# status): the system's dpkg is never told about the architecture (no `dpkg --add-architecture`,
# which would make the host's apt want its versions of everything), nothing is installed, and
# root is not needed. The C and C++ runtimes come from the cross toolchain (/usr/TRIPLET, e.g.
# packages libc6-dev-armhf-cross and libstdc++-12-dev-armhf-cross), not from here.
#
# Usage: scripts/armhf_sysroot.sh [--arch armhf|arm64] [SYSROOT]   (default build/ARCH-sysroot;
# skips the work when the sysroot already holds this package list; delete the folder to refresh
# it)
set -euo pipefail
cd "$(dirname "$0")/.."
arch=armhf
if [ "${1:-}" = --arch ]; then
  arch=${2:-}
  shift 2 || true
fi
case "$arch" in
  armhf) triplet=arm-linux-gnueabihf ;;
  arm64) triplet=aarch64-linux-gnu ;;
  *)
    echo "sysroot: unknown architecture '$arch' (armhf or arm64)" >&2
    exit 2
    ;;
esac
sysroot=$(realpath -m "${1:-build/$arch-sysroot}")
apt_dir=$(realpath -m "$(dirname "$sysroot")/$arch-apt")

# The -dev packages and the runtime packages their .so links point to. The tests link libpng and
# zlib statically (the toolchain file prefers .a), the runtime packages keep the .so links whole.
# libgpiod (1.6) and libusb-1.0 are for the Linux display backends (hal/host/linux,
# hal/host/usb); programs link them as shared libraries, and libudev1 is there because libusb-1.0.so needs it (at link
# time through -rpath-link, at run time in the emulated guest of scripts/ci_guest.sh).
pkgs=(libgtest-dev libpng-dev libpng16-16 zlib1g-dev zlib1g
      libgpiod-dev libgpiod2 libusb-1.0-0-dev libusb-1.0-0 libudev1)

# Up to date: this package list, unpacked for this architecture (its multiarch library folder).
stamp="$sysroot/.lr-sysroot"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "${pkgs[*]}" ] && [ -d "$sysroot/usr/lib/$triplet" ]; then
  echo "$arch sysroot: up to date ($sysroot)"
  exit 0
fi

if ! command -v apt-get >/dev/null || ! command -v dpkg-deb >/dev/null; then
  echo "$arch sysroot: needs apt-get and dpkg-deb (Debian)" >&2
  exit 1
fi

# shellcheck source=scripts/armhf_apt.sh
source "$(dirname "${BASH_SOURCE[0]}")/armhf_apt.sh"
armhf_apt_setup "$apt_dir" "$arch"
mkdir -p "$apt_dir/debs"

echo "$arch sysroot: apt-get update (private state in $apt_dir)"
apt-get "${apt_opts[@]}" -qq update
rm -f "$apt_dir"/debs/*.deb
(cd "$apt_dir/debs" && apt-get "${apt_opts[@]}" -qq download "${pkgs[@]}")

rm -rf "$sysroot"
mkdir -p "$sysroot"
for deb in "$apt_dir"/debs/*.deb; do
  echo "$arch sysroot: unpacking $(basename "$deb")"
  dpkg-deb -x "$deb" "$sysroot"
done
echo "${pkgs[*]}" >"$stamp"
echo "$arch sysroot: done ($sysroot)"
