#!/bin/busybox sh
# shellcheck shell=dash
# PID 1 of the emulated ARM guest that scripts/ci_guest.sh boots (the initramfs's /init): mounts
# the kernel's file systems, loads the USB modules the host script listed in /etc/lr-modules
# (dependencies first), makes a USB device with a configfs gadget on dummy_hcd, runs
# /guest_test, then /lr_panel_app a few times, and powers the guest off. Everything it prints
# goes to the serial console, which the host script reads: the test's PASS/FAIL lines and its
# summary, and lr_panel_app's figures and exit statuses, decide the result.
/bin/busybox mkdir -p /proc /sys /dev /tmp /sbin /usr/bin /usr/sbin
/bin/busybox --install -s
export PATH=/bin:/sbin:/usr/bin:/usr/sbin
export LD_LIBRARY_PATH=/lib

say() { echo "guest-init: $*"; }
finish() {
  say "powering off"
  sync
  poweroff -f
}

mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mount -t debugfs debugfs /sys/kernel/debug
say "kernel $(uname -r), spidev bufsiz $(cat /sys/module/spidev/parameters/bufsiz 2>/dev/null || echo '?')"

while read -r mod; do
  insmod "/lib/modules/$mod" || say "FAIL insmod $mod"
done </etc/lr-modules
mount -t configfs configfs /sys/kernel/config

# The USB device: a SourceSink function (usb_f_ss_lb; mod63 data pattern, checked by the sink)
# on the dummy_hcd device controller, seen by the same kernel's USB host side. IDs: pid.codes'
# test VID:PID; guest_test.cpp looks for them and for this serial number.
udc=
for u in /sys/class/udc/*; do
  [ -e "$u" ] && udc=${u##*/} && break
done
g=/sys/kernel/config/usb_gadget/lr
if [ -n "$udc" ] && mkdir "$g"; then
  echo 0x1209 >"$g/idVendor"
  echo 0x0001 >"$g/idProduct"
  mkdir "$g/strings/0x409"
  echo lr-guest-0001 >"$g/strings/0x409/serialnumber"
  echo lineraster >"$g/strings/0x409/manufacturer"
  echo "guest source/sink" >"$g/strings/0x409/product"
  mkdir "$g/configs/c.1"
  mkdir "$g/functions/SourceSink.0"
  echo 1 >"$g/functions/SourceSink.0/pattern"
  ln -s "$g/functions/SourceSink.0" "$g/configs/c.1/"
  echo "$udc" >"$g/UDC"
  # Wait (at most 10 s) until the host side has enumerated it and devtmpfs made its node.
  found=
  i=0
  while [ $i -lt 100 ] && [ -z "$found" ]; do
    for d in /sys/bus/usb/devices/*; do
      if [ "$(cat "$d/idVendor" 2>/dev/null)" = 1209 ] && [ -f "$d/busnum" ]; then
        node=$(printf '/dev/bus/usb/%03d/%03d' "$(cat "$d/busnum")" "$(cat "$d/devnum")")
        [ -e "$node" ] && found="$node"
      fi
    done
    [ -n "$found" ] || usleep 100000
    i=$((i + 1))
  done
  say "USB gadget on $udc: ${found:-not enumerated}"
else
  say "no USB device controller (dummy_hcd not loaded?)"
fi

say "gpio lines:"
cat /sys/kernel/debug/gpio
say "running /guest_test"
# Bounded here too, so that a hung check ends with a message rather than the host's timeout.
timeout 120 /guest_test
say "guest_test exited with $?"

# lr_panel_app (firmware/linux) on the same spidev and lines, once the test has let them go:
# two frames of the demo scene on a ST7789 240x240, then the device errors (no spidev, no GPIO
# chip: exit 1), a bad option (exit 2) and a run without end stopped by SIGTERM (exit 0). Each run's output is prefixed "panel_app NAME: " and
# ends with "panel_app NAME: exit N"; the host script checks the figures.
spidev=
for s in /sys/class/spidev/*; do
  if [ "$(tr -d '\0' <"$s/device/of_node/compatible" 2>/dev/null)" = rohm,dh2228fv ]; then
    spidev=/dev/${s##*/}
  fi
done
chip=9030000.pl061
lines="dc=$chip:4,rst=$chip:5,bl=$chip:6,hz=10000000"
run_app() {  # NAME ARGS...
  name=$1
  shift
  timeout 120 /lr_panel_app "$@" >/tmp/panel_app.out 2>&1
  rc=$?
  sed "s/^/panel_app $name: /" /tmp/panel_app.out
  echo "panel_app $name: exit $rc"
}
say "running /lr_panel_app on ${spidev:-no spidev}"
run_app frames --display "spidev:$spidev,$lines" --panel st7789:240x240 --frames 2
run_app no_spidev --display "spidev:/dev/spidev9.9,$lines" --panel st7789:240x240 --frames 1
run_app no_chip --display "spidev:$spidev,dc=gpiochip7:4" --panel st7789:240x240 --frames 1
run_app bad_option --display "spidev:$spidev,$lines" --panel st7789:240x240 --frames two
# --frames 0 runs until SIGTERM (or SIGINT), which ends it cleanly after the frame in progress.
/lr_panel_app --display "spidev:$spidev,$lines" --panel st7789:240x240 --frames 0 \
  >/tmp/panel_app.out 2>&1 &
pid=$!
sleep 4
kill -TERM $pid
wait $pid
rc=$?
sed "s/^/panel_app until_term: /" /tmp/panel_app.out
echo "panel_app until_term: exit $rc"
finish
