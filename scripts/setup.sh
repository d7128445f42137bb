#!/bin/bash
# Installs the Debian 12 packages lineraster needs that are missing. Run as root.
# Usage: scripts/setup.sh [demo|test]   (demo: what rendering needs; test: everything)
set -euo pipefail
what=${1:-test}
pkgs=(g++ make cmake libpng-dev libjpeg-dev libgif-dev)  # libgif-dev: lineraster-sim's GIF (optional)
if [ "$what" = test ]; then
  pkgs+=(libgtest-dev libbenchmark-dev valgrind libosmesa6-dev gcc-arm-none-eabi libnewlib-arm-none-eabi
         libstdc++-arm-none-eabi-newlib qemu-system-arm
         g++-arm-linux-gnueabihf g++-aarch64-linux-gnu qemu-user python3-matplotlib
         clang libclang-rt-14-dev
         clang-format clang-tidy  # scripts/format.sh, scripts/tidy.sh (Debian 12: version 14)
         pkg-config libgpiod-dev libusb-1.0-0-dev  # display backends (hal/host)
         device-tree-compiler cpio  # the ARM Linux guest of scripts/ci_guest.sh
         git)  # scripts/consumers.sh: FetchContent of this checkout
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present"
  exit 0
fi
if [ "$(id -u)" != 0 ]; then
  echo "setup: missing packages: ${missing[*]}; run as root (or: sudo apt-get install ${missing[*]})" >&2
  exit 1
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
