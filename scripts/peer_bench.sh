#!/usr/bin/env bash
# The peer scenes as a benchmark of the project (tests/data/peer/README.md: the six scenes on
# which TGX, small3dlib and TinyGL were measured on a Cortex-M4F). Runs the two images of
# firmware/peer of each bare-metal build tree, lr_peer (every span routine linked) and
# lr_peer_spans (each scene's renderer restricted to the span set of its draw state), under QEMU
# with the instruction-counting plugin (scripts/icount.sh) and checks that every case line (frame
# checksum and frame statistics) equals the host build's (lr_peer_host), byte for byte; then
# attributes each frame's instructions to source folders (scripts/icount_profile.py --by folder)
# and prints one Markdown table per core and image (scripts/peer_tables.py), with the PSNR of
# each frame against the double reference and, for the RGB565 frame, against Mesa with the
# pixels covered by one of the two only (lr_peer_psnr, host; tests/firmware_host/peer_figures.hpp
# says how they are measured).
# Benchmark figures: printed, never compared with a threshold. Builds nothing: every program must
# have been built (the message says which target is missing).
#
# Stages, from icount_profile.py's folder rows (inlined code counts where it is written):
#   vertex               core/vertex + core/lighting            per vertex transformed
#   cull + bin           core/binning                            per input triangle
#   setup                core/setup                              per triangle set up ("drawn")
#   spans                core/span + core/texture                per pixel written
#   strip loop + clears  core/raster + core/output + firmware/common (the sink, memset/memcpy)
#                        + libc memset/memcpy if linked          per pixel of the 320x240 frame
#   other                everything else: core/math, core/scene, libgcc's division helpers, ...
# Budgets (the Cortex-M4F ones of the issue "Fast on the chip", printed beside the M4F figures):
#   per frame S1 1.6 M, S1x 16 M, S2n 0.86 M, S2b 3.3 M, S3n 0.70 M, S3b 3.1 M; vertex 120 per
#   vertex, cull + bin 60 per input triangle, setup 250 per drawn Gouraud triangle and 350 per
#   textured one, clears 1 per pixel. TGX's figures: the peer README's (Cortex-M4F).
# Cycles: neither tools/qemu_icount nor these scripts have a cycle model, so the tables print
# "n/a" (instructions are not cycles: divisions and loads take more than one).
# The stages need line tables: configure the cross trees with CXXFLAGS=-g (it does not change the
# code); without them the stage columns say "n/a".
#
# Usage: scripts/peer_bench.sh [--write-docs | --check-only] [build tree ...]
#          (default: build/cortex-m4f build/cortex-m0plus)
#   --check-only   only the checksum comparison (one QEMU run per tree), no profile, no tables
#   --write-docs   also writes docs/measurements/peer_scenes.md (scripts/write_measurements.py)
#   LR_PEER_HOST   the host build (default build/debug/tests/firmware_host/lr_peer_host)
#   LR_PEER_PSNR   the reference comparison (default build/debug/tests/firmware_host/lr_peer_psnr)
#   LR_ICOUNT_PLUGIN  the plugin (scripts/icount.sh's default otherwise)
# Tables also go to out/peer_bench/<tree>.md (lr_peer) and <tree>.spans.md (lr_peer_spans).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

fail() {
  echo "peer_bench: FAIL: $*" >&2
  exit 1
}

write_docs=0
check_only=0
trees=()
for a in "$@"; do
  case "$a" in
    --write-docs) write_docs=1 ;;
    --check-only) check_only=1 ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) fail "unknown option $a (--help)" ;;
    *) trees+=("$a") ;;
  esac
done
((write_docs + check_only < 2)) || fail "--write-docs needs the tables: not with --check-only"
[[ ${#trees[@]} -gt 0 ]] || trees=(build/cortex-m4f build/cortex-m0plus)

host_peer="${LR_PEER_HOST:-build/debug/tests/firmware_host/lr_peer_host}"
psnr_prog="${LR_PEER_PSNR:-build/debug/tests/firmware_host/lr_peer_psnr}"
[[ -x "$host_peer" ]] || fail "$host_peer not built (cmake --build build/debug --target lr_peer_host)"
host_out="$("$host_peer")" || fail "the host build of lr_peer failed: $host_out"
host_cases="$(grep '^lr_bench: case ' <<<"$host_out")"

out=out/peer_bench
mkdir -p "$out"
if ((!check_only)); then
  [[ -x "$psnr_prog" ]] || fail "$psnr_prog not built (cmake --build build/debug --target lr_peer_psnr)"
  "$psnr_prog" >"$out/psnr.txt" || fail "$psnr_prog failed"
fi

tables=()
titles=()
for tree in "${trees[@]}"; do
  list="$tree/firmware/images.txt"
  [[ -f "$list" ]] || fail "$list missing (configure $tree: LR_HOST_TOOLS_DIR=\$PWD/build/debug cmake --preset $(basename "$tree"))"
  core="$(basename "$tree")"
  # lr_peer: every span routine linked; lr_peer_spans: each scene's span set. Both must draw the
  # host's frames.
  for image in lr_peer lr_peer_spans; do
    line="$(grep "^$image " "$list" || true)"
    [[ -n "$line" ]] || fail "no $image image in $list (reconfigure $tree from a source tree with firmware/peer)"
    read -r _ board machine elf <<<"$line"
    [[ -f "$elf" ]] || fail "$elf not built (cmake --build $tree --target $image)"
    if [[ $image == lr_peer ]]; then
      label="$core"
      linked="every span routine linked"
      title="$core"
    else
      label="$core.spans"
      linked="each scene's span set linked"
      title="$core, each scene's span set (lr_peer_spans)"
    fi
    t0=$SECONDS
    run="$(bash scripts/icount.sh --machine "$machine" "$elf" lr_bench_marker)" \
      || { echo "$run" >&2; fail "$image failed under QEMU ($tree)"; }
    target_cases="$(grep '^lr_bench: case ' <<<"$run")"
    [[ -n "$target_cases" && "$target_cases" == "$host_cases" ]] \
      || fail "$core $image frames differ from the host's:"$'\n'"$(diff <(echo "$host_cases") <(echo "$target_cases") || true)"
    echo "peer_bench: $core ($board) $image: $(grep -c '^lr_bench: case ' <<<"$run") frames identical to the host's ($((SECONDS - t0)) s)"
    ((check_only)) && continue

    echo "$run" >"$out/$label.run.txt"
    t0=$SECONDS
    python3 scripts/icount_profile.py --machine "$machine" "$elf" --by folder >"$out/$label.profile.txt" \
      || fail "icount_profile.py failed on $elf"
    echo "peer_bench: $core $image: profiles of every frame ($((SECONDS - t0)) s)"
    table="$out/$label.md"
    {
      echo "**$core** ($image on QEMU $machine: $linked), 320x240 RGB565, strips of 8 rows, default settings (frame = begin_frame + draw + render; the sink does no per-pixel work). Each stage: instructions per frame (per unit$([[ $core == cortex-m4f ]] && echo "; the M4F budget")). PSNR: the core's RGB888 frame against the double reference over the pixels both cover (host). vs Mesa: the RGB565 frame against Mesa's RGB888 frame over the whole frame (the background as the panel shows it), and the pixels covered by one of the two only (host)."
      echo
      python3 scripts/peer_tables.py "$core" "$out/$label.run.txt" "$out/$label.profile.txt" "$out/psnr.txt"
    } >"$table" || fail "could not make the tables ($tree, $image)"
    cat "$table"
    echo
    tables+=("$table")
    titles+=("$title")
  done
done

if ((write_docs)); then
  for i in "${!tables[@]}"; do
    echo "## ${titles[$i]}"
    echo
    cat "${tables[$i]}"
    echo
  done | python3 scripts/write_measurements.py peer_scenes "bash scripts/peer_bench.sh --write-docs" \
    "The peer scenes on Cortex-M4F and M0+"
fi
