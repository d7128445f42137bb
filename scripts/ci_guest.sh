#!/usr/bin/env bash
# The Linux display backends on a real (emulated) 32-bit ARM Linux kernel: boots Debian 12's
# armhf kernel under qemu-system-arm (-M virt) with a small busybox initramfs and runs
# tests/guest/guest_test there, once, with every check in one boot. The guest has
#   - a real GPIO chip: the virt board's PL061 (gpio-pl061), which libgpiod opens;
#   - a real spidev: a spi-gpio bus over PL061 lines with a spidev child, added to QEMU's own
#     device tree (tests/guest/virt_spi_gpio.dtsi), spidev's buffer cut to 1024 bytes
#     (spidev.bufsiz=1024) so that pixel transfers have to be split;
#   - a real USB device: a configfs gadget (SourceSink function) on dummy_hcd, enumerated by the
#     same kernel's USB host side, which libusb opens and transfers to.
# tests/guest/init.sh (the initramfs's /init) sets that up, runs the test and powers off; this
# script reads the serial console and fails unless every check printed PASS. The test
# (tests/guest/guest_test.cpp, linked with lr_hal_linux and lr_hal_usb) opens SpidevBus on that
# spidev with D/C, reset and backlight on PL061 lines and reads the lines back, sends commands
# and a 320x240 RGB565 frame (150 transfers), runs out a bounded wait and a failing transfer,
# checks the one-line errors (wrong device, line busy, no chip, no line), and moves data both
# ways through UsbBulk on the gadget (the gadget's sink checks every byte). Then it runs
# lr_panel_app (firmware/linux, the demo scene through the panel driver and PanelSink) on the same
# spidev and lines for two frames and checks the bytes each frame sent (the figures of
# tests/panel_app/panel_app_test.cpp: frames are bit-identical on every platform), and its exit
# statuses for a missing spidev, a missing GPIO chip (1) and a bad option (2), and a run without
# a frame count that SIGTERM ends cleanly (0).
#
# Usage: scripts/ci_guest.sh   (from any directory; as root it installs missing host packages:
#                               qemu-system-arm, device-tree-compiler, cpio,
#                               g++-arm-linux-gnueabihf, pkgconf, qemu-user)
#   LR_GUEST_TIMEOUT=300   seconds the whole boot may take (default 300)
#
# Everything comes from Debian 12's packages: the kernel (linux-image-armmp's current
# linux-image-*-armmp) and busybox-static for armhf are fetched with apt-get download through a
# private apt configuration in build/guest/apt (like scripts/armhf_sysroot.sh: the host's dpkg
# never learns about armhf, nothing is installed), libgpiod and libusb for armhf come from the
# armhf sysroot (scripts/armhf_sysroot.sh), the C and C++ runtimes from the cross toolchain.
# lr_panel_app's mesh header is generated at build time by lineraster-asset built for armhf and
# run under qemu-arm (qemu-user), as in the armhf test build.
# Downloads and unpacked packages are kept under build/guest and reused; delete build/guest/debs
# to fetch the current packages again.
# Exit status: 0 when every check passed, 1 otherwise (with a message saying what failed).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
work="$repo_root/build/guest"
timeout_s=${LR_GUEST_TIMEOUT:-300}
jobs=$(nproc)
triplet=arm-linux-gnueabihf
toolchain_root=/usr/$triplet
sysroot="$repo_root/build/armhf-sysroot"

# The machine: the same options for dumping QEMU's device tree and for the boot (the tree
# depends on them). highmem=off: the armmp kernel is not LPAE, so nothing may sit above 4 GB.
# No network: the default virtio NIC needs efi-virtio.rom (ipxe-qemu), which a minimal install lacks.
machine=(-M "virt,highmem=off" -cpu cortex-a15 -smp 1 -m 256 -nic none)
# spi-gpio, spidev and gpio-pl061 are built into Debian's armmp kernel; the USB pieces are modules.
wanted_modules=(gpio_pl061 spi_gpio spidev dummy_hcd libcomposite usb_f_ss_lb)
spidev_bufsiz=1024

fail() {
  echo "ci_guest: FAIL: $*" >&2
  exit 1
}
elapsed() {
  echo "ci_guest: $1 took $((SECONDS - $2)) s"
}

# ---- host tools
declare -A tool_pkg=(
  [qemu-system-arm]=qemu-system-arm [dtc]=device-tree-compiler [cpio]=cpio
  [$triplet-g++]=g++-$triplet [$triplet-readelf]=binutils-$triplet
  [$triplet-objcopy]=binutils-$triplet [cmake]=cmake [pkg-config]=pkgconf [timeout]=coreutils
  [qemu-arm]=qemu-user
)
missing=()
for tool in "${!tool_pkg[@]}"; do
  command -v "$tool" >/dev/null 2>&1 || missing+=("${tool_pkg[$tool]}")
done
if [ ${#missing[@]} -gt 0 ]; then
  mapfile -t missing < <(printf '%s\n' "${missing[@]}" | sort -u)
  [ "$(id -u)" = 0 ] || fail "missing host packages: ${missing[*]} (run as root, or apt-get install them)"
  echo "ci_guest: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
for tool in apt-get dpkg-deb; do
  command -v "$tool" >/dev/null 2>&1 || fail "$tool not found (Debian needed)"
done
echo "ci_guest: $(qemu-system-arm --version | head -n 1); $($triplet-g++ --version | head -n 1)"

# ---- downloads: the armhf sysroot (libgpiod, libusb), the kernel and busybox
t=$SECONDS
bash scripts/armhf_sysroot.sh || fail "could not build the armhf sysroot (scripts/armhf_sysroot.sh)"

apt_dir="$work/apt"
debs="$work/debs"
guest_pkgs=(linux-image-armmp busybox-static)
stamp="$debs/.lr-guest-debs"
if [ -f "$stamp" ] && [ "$(head -n 1 "$stamp")" = "${guest_pkgs[*]}" ]; then
  echo "ci_guest: kernel and busybox packages up to date ($debs)"
else
  # shellcheck source=scripts/armhf_apt.sh
  source scripts/armhf_apt.sh
  armhf_apt_setup "$apt_dir"
  mkdir -p "$debs"
  echo "ci_guest: apt-get update (private state in $apt_dir)"
  apt-get "${apt_opts[@]}" -qq update
  # linux-image-armmp is a meta-package: fetch the versioned image it depends on.
  kernel_pkg=$(apt-cache "${apt_opts[@]}" depends linux-image-armmp \
    | sed -n 's/^ *Depends: \(linux-image-[0-9][^ ]*-armmp\)$/\1/p' | head -n 1)
  [ -n "$kernel_pkg" ] || fail "could not resolve linux-image-armmp to a kernel package"
  rm -f "$debs"/*.deb
  (cd "$debs" && apt-get "${apt_opts[@]}" -qq download "$kernel_pkg" busybox-static) \
    || fail "apt-get download $kernel_pkg busybox-static failed"
  printf '%s\n%s\n' "${guest_pkgs[*]}" "$kernel_pkg" >"$stamp"
fi
shopt -s nullglob
kernel_debs=("$debs"/linux-image-*-armmp_*.deb)
busybox_debs=("$debs"/busybox-static_*.deb)
shopt -u nullglob
if [ ${#kernel_debs[@]} != 1 ] || [ ${#busybox_debs[@]} != 1 ]; then
  fail "expected one kernel and one busybox package in $debs (delete the folder to fetch them again)"
fi
kernel_deb=${kernel_debs[0]}
busybox_deb=${busybox_debs[0]}

# Unpacked once per package file.
unpack() {  # deb dir
  if [ "$(cat "$2/.lr-deb" 2>/dev/null)" != "$(basename "$1")" ]; then
    echo "ci_guest: unpacking $(basename "$1")"
    rm -rf "$2"
    mkdir -p "$2"
    dpkg-deb -x "$1" "$2"
    basename "$1" >"$2/.lr-deb"
  fi
}
unpack "$kernel_deb" "$work/kernel"
unpack "$busybox_deb" "$work/busybox"
kver=$(dpkg-deb -f "$kernel_deb" Package)
kver=${kver#linux-image-}
vmlinuz="$work/kernel/boot/vmlinuz-$kver"
[ -f "$vmlinuz" ] || fail "no $vmlinuz in $(basename "$kernel_deb")"
moddir="$work/kernel/lib/modules/$kver"
[ -f "$moddir/modules.order" ] || fail "no modules.order in $moddir"
elapsed "downloads (sysroot, kernel $kver, busybox)" "$t"

# ---- the guest's programs (guest_test, lr_panel_app), cross-built with the project's toolchain
t=$SECONDS
testbuild="$work/test-build"
# At -O1, as the armhf preset (CMakePresets.json): what the guest checks is the kernel's side
# of the backends, not the optimiser's; -O3 took twice the compile time.
cmake -S tests/guest -B "$testbuild" -DCMAKE_TOOLCHAIN_FILE="$repo_root/toolchain/$triplet.cmake" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" >/dev/null || fail "configure of tests/guest failed"
cmake --build "$testbuild" -j"$jobs" || fail "guest build failed (see the compiler output above)"
guest_test="$testbuild/guest_test"
panel_app=$(cat "$testbuild/lr_panel_app.path" 2>/dev/null || true)
[ -x "$panel_app" ] || fail "lr_panel_app not built (${panel_app:-no $testbuild/lr_panel_app.path})"
elapsed "guest programs build" "$t"

# ---- the initramfs: busybox, /init, the test with its shared libraries, the USB modules
t=$SECONDS
root="$work/initramfs"
rm -rf "$root"
mkdir -p "$root"/{bin,lib/modules,etc,proc,sys,dev,tmp}
cp "$work/busybox/bin/busybox" "$root/bin/busybox"
cp tests/guest/init.sh "$root/init"
chmod 755 "$root/init"
cp "$guest_test" "$root/guest_test"
cp "$panel_app" "$root/lr_panel_app"

# Shared libraries: the NEEDED entries, found in the sysroot or the toolchain's root, copied
# into /lib (the init script sets LD_LIBRARY_PATH=/lib) with the dynamic loader.
lib_dirs=("$sysroot/usr/lib/$triplet" "$sysroot/lib/$triplet" "$toolchain_root/lib")
copy_needed() {  # elf
  local lib dir found
  for lib in $($triplet-readelf -d "$1" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
    [ -e "$root/lib/$lib" ] && continue
    found=
    for dir in "${lib_dirs[@]}"; do
      if [ -e "$dir/$lib" ]; then
        cp -L "$dir/$lib" "$root/lib/$lib"
        found=1
        break
      fi
    done
    [ -n "$found" ] || fail "shared library $lib (needed by $(basename "$1")) not found in ${lib_dirs[*]}"
    copy_needed "$root/lib/$lib"
  done
}
copy_needed "$guest_test"
copy_needed "$panel_app"
interp=$($triplet-readelf -l "$guest_test" | sed -n 's/.*interpreter: \(.*\)\]/\1/p')
if [ -z "$interp" ] || [ ! -e "$toolchain_root/lib/$(basename "$interp")" ]; then
  fail "dynamic loader ${interp:-?} not found in $toolchain_root/lib"
fi
mkdir -p "$root$(dirname "$interp")"
cp -L "$toolchain_root/lib/$(basename "$interp")" "$root$interp"

# Kernel modules: each wanted one that is not built in, after the modules it depends on (the
# `depends=` of its .modinfo section; the package ships no modules.dep, depmod runs at install).
declare -A mod_path=()
while read -r rel; do
  name=${rel##*/}
  name=${name%.ko}
  mod_path[${name//-/_}]=$rel
done <"$moddir/modules.order"
declare -A mod_done=()
load_list=()
add_module() {  # name
  local name=${1//-/_} rel dep deps
  [ -n "${mod_done[$name]:-}" ] && return 0
  mod_done[$name]=1
  rel=${mod_path[$name]:-}
  [ -n "$rel" ] || fail "kernel module $name is neither built in nor in $moddir"
  [ -f "$moddir/$rel" ] || fail "kernel module file $moddir/$rel missing"
  $triplet-objcopy -O binary --only-section=.modinfo "$moddir/$rel" "$work/modinfo.bin"
  deps=$(tr '\0' '\n' <"$work/modinfo.bin" | sed -n 's/^depends=//p' | tr ',' ' ')
  for dep in $deps; do
    add_module "$dep"
  done
  mkdir -p "$root/lib/modules/$(dirname "$rel")"
  cp "$moddir/$rel" "$root/lib/modules/$rel"
  if [ "$name" = spidev ]; then
    load_list+=("$rel bufsiz=$spidev_bufsiz")
  else
    load_list+=("$rel")
  fi
}
for m in "${wanted_modules[@]}"; do
  if grep -qE "/${m//_/[-_]}\.ko$" "$moddir/modules.builtin"; then
    continue
  fi
  add_module "$m"
done
printf '%s\n' "${load_list[@]}" >"$root/etc/lr-modules"
echo "ci_guest: modules to load: $(printf '%s ' "${load_list[@]##*/}")"

initramfs="$work/initramfs.cpio"
(cd "$root" && find . -mindepth 1 | LC_ALL=C sort | cpio -o -H newc --quiet -R 0:0) >"$initramfs"
echo "ci_guest: initramfs $(($(stat -c %s "$initramfs") / 1024)) KB"

# ---- the device tree: QEMU's own for this machine, plus the spi-gpio bus
rm -f "$work/virt.dtb"
qemu-system-arm "${machine[@]}" -machine dumpdtb="$work/virt.dtb" -display none >/dev/null 2>&1 || true
[ -s "$work/virt.dtb" ] || fail "qemu-system-arm could not dump the virt device tree"
dtc -q -I dtb -O dts -o "$work/virt.dts" "$work/virt.dtb" || fail "dtc could not decompile the virt device tree"
cat "$work/virt.dts" tests/guest/virt_spi_gpio.dtsi >"$work/guest.dts"
dtc -q -I dts -O dtb -o "$work/guest.dtb" "$work/guest.dts" \
  || fail "dtc could not compile $work/guest.dts (tests/guest/virt_spi_gpio.dtsi)"
elapsed "initramfs and device tree" "$t"

# ---- the boot
t=$SECONDS
log="$work/console.log"
echo "ci_guest: booting (at most $timeout_s s); serial console:"
set +e
timeout "$timeout_s" qemu-system-arm "${machine[@]}" \
  -kernel "$vmlinuz" -initrd "$initramfs" -dtb "$work/guest.dtb" \
  -append "console=ttyAMA0 quiet panic=-1 spidev.bufsiz=$spidev_bufsiz" \
  -display none -monitor none -serial stdio -no-reboot </dev/null 2>&1 | tr -d '\r' | tee "$log"
status=${PIPESTATUS[0]}
set -e
elapsed "boot and checks" "$t"
[ "$status" != 124 ] || fail "the guest did not power off within $timeout_s s (console: $log)"
[ "$status" = 0 ] || fail "qemu-system-arm exited with status $status (console: $log)"

# ---- the verdict
summary=$(grep -E '^guest: [0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1 || true)
[ -n "$summary" ] || fail "no summary line from guest_test (it did not run or crashed; console: $log)"
passed=$(echo "$summary" | sed -E 's/^guest: ([0-9]+) passed.*/\1/')
failed=$(echo "$summary" | sed -E 's/.* ([0-9]+) failed$/\1/')
pass_lines=$(grep -c '^PASS ' "$log" || true)
fail_lines=$(grep -c '^FAIL ' "$log" || true)
init_fail=$(grep -c '^guest-init: FAIL' "$log" || true)
[ "$init_fail" = 0 ] || fail "the guest's init script reported failures (see guest-init: FAIL above)"
if [ "$failed" != 0 ] || [ "$fail_lines" != 0 ]; then
  fail "$failed of $((passed + failed)) guest checks failed (see the FAIL lines above)"
fi
if [ "$passed" = 0 ] || [ "$pass_lines" != "$passed" ]; then
  fail "the summary ($summary) does not match the $pass_lines PASS lines"
fi

# ---- lr_panel_app's runs (tests/guest/init.sh): figures and exit statuses
# What PanelSink sent for each frame of the ST7789 240x240, as tests/panel_app/panel_app_test.cpp
# asserts on the host (keep them in step): frame 0 everything, 30 strips of 8 rows, each CASET,
# RASET and RAMWR (11 bytes) and 3,840 pixel bytes; frame 1, 3 degrees on, 13 strips unchanged
# (skipped) and 17 narrowed to their changed columns.
app_frames=(
  "frame=0 degrees=0 bytes=115530 pixel_bytes=115200 command_bytes=330 strips_sent=30 strips_narrowed=0 strips_skipped=0 "
  "frame=1 degrees=3 bytes=30907 pixel_bytes=30720 command_bytes=187 strips_sent=17 strips_narrowed=17 strips_skipped=13 "
  "frames=2 bytes=146437 pixel_bytes=145920 "
)
app_failed=0
starts_a_line() {  # TEXT PREFIX
  local line
  while IFS= read -r line; do
    [[ "$line" == "$2"* ]] && return 0
  done <<<"$1"
  return 1
}
app_check() {  # NAME EXIT-STATUS LINE-PREFIX...: each prefix must start a line of NAME's output
  local name=$1 status=$2 out prefix ok=1
  shift 2
  out=$(sed -n "s/^panel_app $name: //p" "$log")
  starts_a_line "$out" "exit $status" || ok=
  for prefix in "$@"; do
    starts_a_line "$out" "$prefix" || ok=
  done
  if [ -n "$ok" ]; then
    echo "ci_guest: PASS lr_panel_app $name (exit $status)"
  else
    echo "ci_guest: FAIL lr_panel_app $name: expected exit $status and lines starting with: $*" >&2
    app_failed=$((app_failed + 1))
  fi
}
app_check frames 0 "lr_panel_app: st7789 240x240" "${app_frames[@]}"
app_check no_spidev 1 "lr_panel_app: /dev/spidev9.9: no such device"
app_check no_chip 1 "lr_panel_app: gpiochip7: no such GPIO chip"
app_check bad_option 2 "lr_panel_app: --frames: bad value 'two'"
# --frames 0 stopped by SIGTERM after 4 s: a clean end with its summary, whatever the count.
app_check until_term 0 "frame=0 degrees=0 bytes=115530 " "frames="
# Each error is one line: the run's output is that line and its exit status.
for name in no_spidev no_chip bad_option; do
  n=$(grep -c "^panel_app $name: " "$log" || true)
  if [ "$n" != 2 ]; then
    echo "ci_guest: FAIL lr_panel_app $name printed $((n - 1)) lines, not one" >&2
    app_failed=$((app_failed + 1))
  fi
done
[ "$app_failed" = 0 ] || fail "$app_failed lr_panel_app checks failed (its output is above, prefixed panel_app)"
echo "ci_guest: lr_panel_app on the guest's spidev:"
sed -n 's/^panel_app frames: /  /p' "$log"
echo "ci_guest: PASS ($passed checks on the emulated ARM Linux guest, kernel $kver; lr_panel_app: 5 runs)"
