#!/usr/bin/env bash
# Footprint report of the firmware configurations: flash, RAM and worst-case stack of each
# footprint image (firmware/footprint: unlit, gouraud, tex_nearest, tex_bilinear, phong, ... at
# 320x240, RGB565, strips of 8 rows, storage for 1,000 triangles), and the link guard.
#
#   bash scripts/footprint.sh [--write-docs] [BUILD_DIR ...]
#                                     (default: build/cortex-m0plus build/cortex-m4f; CI adds
#                                     build/cortex-m4f-size, the -Os preset)
#
# For each bare-metal build tree that exists (others are skipped with a note):
#   1. builds the footprint images (cmake --build -j2 --target lr_fp_*);
#   2. link guard: no heap, exception support, soft-float helper or FPU arithmetic in ANY .elf
#      of the tree (the rules, shared with scripts/ci_cross.sh: scripts/lib/firmware_rules.sh);
#   3. per image: flash = every loaded byte (vector table, code, .rodata, unwind index, init
#      arrays, and .data's load image: objdump -h sections with LOAD); RAM = .data + .bss (the
#      ALLOC sections in the map file's RAM region), without the reserved .stack section, whose
#      need is the stack column; worst-case stack = scripts/stack_usage.py's total: the reset
#      path (Reset_Handler -> main -> ...) plus every exception handler of the vector table with
#      its exception frame, nested (an upper bound);
#   4. runs each image under QEMU (its board's machine, with a timeout): the frame must be
#      complete, and the stack high-water mark the image measures (stack_probe.hpp) must not
#      exceed the static bound of the reset path — a static analysis that underestimates fails
#      here. Frames of the same configuration must be identical on every core (integer code);
#   5. prints a markdown table per core (with the renderer's own flash: the image minus the
#      empty image lr_fp_empty minus the scene's mesh and texture arrays; and the renderer
#      alone: the core/ and hal/ code and tables the program's calls reach, without the
#      program's own camera, sink and main: scripts/flash_by_folder.py --renderer), the RAM breakdown by
#      store (the sizes the phong image prints), the gouraud_diffuse image's flash by source
#      folder (the Gouraud family without specular, as the peer scenes draw: issue 36's budget)
#      (scripts/flash_by_folder.py), and, for Cortex-M0+ trees, which configurations fit the
#      micro:bit (flash <= its FLASH, RAM + worst-case stack <= its RAM;
#      firmware/common/microbit.ld).
#      With --write-docs the report goes to docs/measurements/footprint.md when every check
#      passed (scripts/write_measurements.py); it is then printed at the end, not as it runs.
# Exit status: non-zero on any failure (guard, analysis, run, bound, missing tools).
set -uo pipefail

cd "$(dirname "$0")/.."
root=$PWD
# shellcheck source=scripts/lib/firmware_rules.sh
source scripts/lib/firmware_rules.sh
prefix=arm-none-eabi-
qemu_timeout=${LR_FOOTPRINT_QEMU_TIMEOUT:-120}
configs=(unlit gouraud tex_nearest tex_bilinear phong gouraud_tex every_feature tex_nearest_shared
         gouraud_diffuse)
status=0

fail() {
  echo "footprint: FAIL: $*" >&2
  status=1
}

# 12345 -> 12,345
group() { sed -e ':a' -e 's/\B[0-9]\{3\}\>/,&/' -e 'ta' <<<"$1"; }

for tool in "${prefix}objdump" "${prefix}nm" "${prefix}readelf" python3 qemu-system-arm; do
  command -v "$tool" >/dev/null || { echo "footprint: $tool not found (bash scripts/setup.sh test)" >&2; exit 1; }
done

# Bytes an ELF loads into flash: its sections with LOAD (objdump -h).
loaded_bytes() {
  local n=0 size flags
  while read -r _ _ size _ _ _ _ flags; do
    [[ $flags == *LOAD* ]] && n=$((n + 16#$size))
  done < <("${prefix}objdump" -h "$1" | sed -n '/^ *[0-9][0-9]* /{N;s/\n */ /;p}')
  echo "$n"
}

# The limits of the micro:bit (firmware/common/microbit.ld), in bytes.
ld_length() {  # ld_length REGION FILE
  local v
  v=$(awk -v r="$1" '$1 == r { for (i = 1; i <= NF; i++) if ($i ~ /^LENGTH/) { s = $0; sub(/.*LENGTH *= */, "", s); print s } }' "$2" | head -1)
  case "$v" in
    *K) echo $(( ${v%K} * 1024 )) ;;
    *M) echo $(( ${v%M} * 1024 * 1024 )) ;;
    *) echo $(( v )) ;;
  esac
}
microbit_ld=firmware/common/microbit.ld
if [[ -f $microbit_ld ]]; then
  mb_flash=$(ld_length FLASH $microbit_ld)
  mb_ram=$(ld_length RAM $microbit_ld)
else
  mb_flash=$((256 * 1024)) mb_ram=$((16 * 1024))
fi

# Symbols (nm -C, from the start of the name) no untextured image may hold (see below).
lr_fp_untextured_unlinked='^(lr::light_point_split|lr::light_point_at|lr::light_point|lr::transform_affine|lr::VertexStage::light_face|lr::VertexStage::attributes|lr::transform_tangent|lr::DrawRecords::phong_record|lr::FrontEnd::run_screen|lr::detail::kMaterialTable|lr::find_material|lr::to_material|(lr::ColorPlanes )?lr::setup_planes|(void )?lr::legacy_rows|lr::FrontEnd::bin_band|lr::FrontEndParts::(shrink_band|compact_vertices|polygon_outside_band|sign_)|(unsigned long )?lr::FrontEnd::general_triangles<(true|false, true)|lr::EdgeTable::shrink_window|lr::VertexStore::(begin_cache|cache_corners|persist)|lr::front_facing_clip|lr::StripLoop<.*>::(skip_strip|crowded_strip)|lr::InputHash::|(int )?lr::clip_polygon<)\b'
# The project's API the footprint program calls for itself, not the renderer (its camera and
# model matrix, firmware/footprint/main.cpp): the program's bytes, unless the renderer calls them.
program_api_names="lr::perspective, lr::look_at, lr::rotate_y"
program_api=()
for n in ${program_api_names//,/}; do program_api+=(--program-api "$n"); done
declare -A checksum_of  # config -> "core checksum" of the first core that ran it
write_docs=0
trees=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else trees+=("$a"); fi
done
[[ ${#trees[@]} -gt 0 ]] || trees=(build/cortex-m0plus build/cortex-m4f)
if ((write_docs)); then
  report=$(mktemp)
  exec 3>&1 >"$report"  # the report, printed (and written to the docs) after the last tree
fi

for tree in "${trees[@]}"; do
  if [[ ! -f $tree/CMakeCache.txt ]]; then
    echo "footprint: note: $tree is not configured: skipped (cmake --preset ${tree##*/})"
    echo
    continue
  fi
  core=$(sed -n 's|^CMAKE_TOOLCHAIN_FILE:[A-Z]*=.*/\(.*\)\.cmake$|\1|p' "$tree/CMakeCache.txt")
  core=${core:-${tree##*/}}
  manifest=$tree/firmware/footprint/footprint_images.txt
  # A tree configured before firmware/footprint/ existed does not know the images yet.
  [[ -f $manifest ]] || cmake "$tree" >/dev/null || { fail "$tree: cmake could not reconfigure"; continue; }
  [[ -f $manifest ]] || { fail "$tree: no firmware/footprint images (not a bare-metal tree?)"; continue; }
  targets=()
  for cfg in "${configs[@]}"; do targets+=(--target "lr_fp_$cfg"); done
  # The empty image in a second call: a tree from before it existed knows the target only once
  # the first call has regenerated the build system.
  if ! { cmake --build "$tree" -j2 "${targets[@]}" &&
         cmake --build "$tree" -j2 --target lr_fp_empty; } >"$tree/footprint_build.log" 2>&1; then
    tail -30 "$tree/footprint_build.log" >&2
    fail "$tree: building the footprint images failed ($tree/footprint_build.log)"
    continue
  fi

  # ---- Link guard: every ELF of the tree (the rules: scripts/lib/firmware_rules.sh).
  elfs=0 clean=0
  while IFS= read -r elf; do
    elfs=$((elfs + 1))
    if found=$(lr_fw_guard "$elf"); then
      clean=$((clean + 1))
    else
      fail "link guard: $elf:"$'\n'"$(sed 's/^/    /' <<<"$found")"
    fi
  done < <(find "$tree" -name '*.elf' -type f | sort)

  # The optimisation level of the tree (CMakePresets.json: cortex-*, -o2, -size).
  build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$tree/CMakeCache.txt")
  release_flags=$(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' "$tree/CMakeCache.txt")
  case $build_type in
    MinSizeRel) opt=-Os ;;
    Release) opt=$(grep -o -- '-O[0-3s]' <<<"${release_flags:--O3}" | tail -1) ;;
    *) opt=$build_type ;;
  esac
  # The baseline: the empty image's loaded bytes (startup, semihosting, no renderer).
  empty_elf=$(find "$tree/firmware/footprint" -name lr_fp_empty.elf | head -1)
  empty_flash=$(loaded_bytes "$empty_elf")

  echo "### $core at $opt ($tree)"
  echo
  echo "Link guard ($lr_fw_guard_what): $clean of $elfs ELFs clean."
  echo
  echo "| configuration | flash | renderer flash | renderer alone | RAM | worst-case stack | measured stack (QEMU) | main alone (static) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  gouraud_split=""
  fits=() misfits=()
  breakdown=""
  while read -r cfg elf machine board; do
    [[ -n $cfg ]] || continue
    map=${elf%.elf}.map
    # Flash: loaded bytes. RAM: ALLOC sections inside the RAM region, .stack excluded.
    read -r ram_org ram_len < <(awk '$1 == "RAM" && $2 ~ /^0x/ {print $2, $3; exit}' "$map")
    if [[ -z ${ram_len:-} ]]; then
      fail "$core $cfg: no RAM region in $map"
      continue
    fi
    flash=0 ram=0 stack_size=0
    while read -r _ name size vma _ _ _ flags; do
      size=$((16#$size)) vma=$((16#$vma))
      [[ $flags == *LOAD* ]] && flash=$((flash + size))
      [[ $name == .stack ]] && stack_size=$size && continue
      if [[ $flags == *ALLOC* ]] && (( vma >= ram_org && vma < ram_org + ram_len )); then
        ram=$((ram + size))
      fi
    done < <("${prefix}objdump" -h "$elf" | sed -n '/^ *[0-9][0-9]* /{N;s/\n */ /;p}')
    # Worst-case stack.
    su_out=$(python3 scripts/stack_usage.py "$elf" "$tree" --vector-table .isr_vector --entry main \
             "${lr_fw_stack_rules[@]}" --tool-prefix "$prefix" --machine 2>&1 </dev/null)
    if [[ $? -ne 0 ]]; then
      fail "$core $cfg: stack analysis: $su_out"
      continue
    fi
    total=$(awk -F'\t' '$1 == "total" {print $2}' <<<"$su_out")
    reset_bound=$(awk -F'\t' '$1 == "entry" && $2 == "Reset_Handler" {print $3}' <<<"$su_out")
    main_bound=$(awk -F'\t' '$1 == "entry" && $2 == "main" {print $3}' <<<"$su_out")
    if (( stack_size > 0 && total > stack_size )); then
      fail "$core $cfg: worst-case stack $total B exceeds the reserved .stack of $stack_size B"
    fi
    # Run it: the measured high-water mark must stay within the static bound.
    run=$(timeout "$qemu_timeout" qemu-system-arm -M "$machine" -nographic -monitor none \
          -semihosting -kernel "$elf" </dev/null 2>&1)
    rc=$?
    measured=$(sed -n 's/^footprint: stack used \([0-9]*\).*/\1/p' <<<"$run")
    sum=$(sed -n 's/^footprint: checksum \(0x[0-9a-f]*\).*/\1/p' <<<"$run")
    if [[ $rc -ne 0 ]] || ! grep -q '^footprint: PASS' <<<"$run" || [[ -z $measured ]]; then
      fail "$core $cfg: the image did not run to PASS under qemu-system-arm -M $machine (status $rc):"$'\n'"$run"
      measured="—"
    elif [[ $measured -gt $reset_bound ]]; then
      fail "$core $cfg: measured stack $measured B > static bound $reset_bound B (Reset_Handler): the analysis underestimates"
    fi
    if [[ -n $sum ]]; then
      if [[ -n ${checksum_of[$cfg]:-} && ${checksum_of[$cfg]#* } != "$sum" ]]; then
        fail "$cfg: frame checksum $sum on $core differs from ${checksum_of[$cfg]}"
      fi
      checksum_of[$cfg]=${checksum_of[$cfg]:-"$core $sum"}
    fi
    [[ $measured != "—" ]] && measured="$(group "$measured") B"
    # The renderer's own flash: the image minus the empty image minus the scene's mesh and
    # texture arrays (the lr::fw::footprint::k* objects, firmware/footprint/scene.hpp).
    assets=$("${prefix}nm" -S -C "$elf" | python3 -c '
import sys
print(sum(int(f[1], 16) for f in (l.split(None, 3) for l in sys.stdin)
          if len(f) == 4 and f[3].startswith("lr::fw::footprint::k")))')
    renderer=$((flash - empty_flash - assets))
    # The renderer alone: the symbols the program's references reach in core/ and hal/, and
    # the libgcc helpers and tables they use (scripts/flash_by_folder.py --renderer); not the
    # program's camera and model matrix (its calls of the API below), sink, main and startup.
    if split=$(python3 scripts/flash_by_folder.py "$elf" --exclude 'lr::fw::footprint::k' \
                 --tool-prefix "$prefix" --renderer "${program_api[@]}"); then
      alone="$(group "$(awk '$1 == "renderer" {print $2}' <<<"$split")") B"
      [[ $cfg == gouraud_diffuse ]] && gouraud_split=$split
    else
      fail "$core $cfg: scripts/flash_by_folder.py --renderer failed"
      alone="—"
    fi
    echo "| $cfg | $(group "$flash") B | $(group "$renderer") B | $alone | $(group "$ram") B | $(group "$total") B | $measured | $(group "$main_bound") B |"
    # What the untextured images must not link: the routines of draws their span set refuses
    # (renderer.hpp's FrontEndRoutines: flat shading's face lighting, point lighting, textured
    # and Phong vertex attributes and their clipper, Phong records; the textured and Phong setup
    # and row loop),
    # draw_screen's binning (the images never call it), the material table (they name their
    # materials at compile time), and the features their renderer leaves out (kNoFeatures,
    # core/raster/renderer_features.hpp: bands, the vertex cache, two-sided lighting's clipped
    # back-face test, strip signatures, the crowded strips' passes, the clipper).
    if [[ $cfg == unlit || $cfg == gouraud || $cfg == gouraud_diffuse ]]; then
      linked=$("${prefix}nm" -C "$elf" | awk '{ $1 = ""; $2 = ""; print substr($0, 3) }' |
               grep -E "${lr_fp_untextured_unlinked}" | sed 's/(.*//' | sort -u)
      [[ -z $linked ]] || fail "$core $cfg links what its span set leaves out:"$'\n'"$(sed 's/^/    /' <<<"$linked")"
    fi
    # Renderers without specular (unlit, gouraud_diffuse: RendererFeatures::specular left out)
    # link no specular power tables.
    if [[ $cfg == unlit || $cfg == gouraud_diffuse ]]; then
      linked=$("${prefix}nm" -C "$elf" | grep -E ' lr::PowTable<' | sed 's/^.* [A-Za-z] //; s/(.*//' | sort -u)
      [[ -z $linked ]] || fail "$core $cfg links the specular term without RendererFeatures::specular:"$'\n'"$(sed 's/^/    /' <<<"$linked")"
    fi
    if (( flash <= mb_flash && ram + total <= mb_ram )); then
      fits+=("$cfg")
    else
      misfits+=("$cfg needs $(group $((ram + total))) B of RAM with its stack and $(group "$flash") B of flash")
    fi
    # The store breakdown, from the image with every store (Phong: also its surfaces).
    if [[ $cfg == phong ]]; then
      declare -A st=()
      # The image prints its stores' sizes in this order (firmware/footprint/main.cpp).
      read -r -a sizes <<<"$(sed -n 's/^footprint: stores \(.*\)/\1/p' <<<"$run")"
      names=(vertices triangles buckets active active_index depth strip_buffers draws surfaces pixel_lights tex_vertices active_extra)
      for i in "${!names[@]}"; do st[${names[$i]}]=${sizes[$i]:-0}; done
      all=0
      for k in "${!st[@]}"; do all=$((all + st[$k])); done
      breakdown="vertex store $(group "${st[vertices]:-0}") B, triangles $(group $(( ${st[triangles]:-0} + ${st[buckets]:-0} ))) B (with $(group "${st[buckets]:-0}") B of strip bucket heads), active $(group $(( ${st[active]:-0} + ${st[active_index]:-0} ))) B (with $(group "${st[active_index]:-0}") B of index), extra planes of textured and Phong triangles $(group "${st[active_extra]:-0}") B, texture entries $(group "${st[tex_vertices]:-0}") B, depth strip $(group "${st[depth]:-0}") B, strip buffers $(group "${st[strip_buffers]:-0}") B, draw records $(group "${st[draws]:-0}") B, surfaces for Phong $(group $(( ${st[surfaces]:-0} + ${st[pixel_lights]:-0} ))) B (with $(group "${st[pixel_lights]:-0}") B of prepared lighting); $(group "$all") B in all"
      unset st
    fi
  done <"$manifest"
  echo
  echo "Flash: every byte loaded into flash (vector table, code, .rodata, unwind index, and the .data load image); renderer flash: that minus the empty image's ($(group "$empty_flash") B: startup, C library shims, semihosting; firmware/footprint/empty.cpp) minus the scene's mesh and texture arrays; renderer alone: the renderer's code and tables only (the core/ and hal/ symbols the program's calls reach, with the libgcc helpers and tables they use; without the program's main, sink, startup and C library shims, and without the API functions only the program calls: its camera and model matrix, ${program_api_names}; what the compiler inlines into the program's functions counts as the program's, as Renderer::render() in main at -O3; scripts/flash_by_folder.py --renderer); RAM: .data + .bss, without the reserved .stack section; worst-case stack: the reset path (Reset_Handler -> main -> ...) plus every exception handler with its exception frame, nested (scripts/stack_usage.py); measured: the stack high-water mark of the run (a lower bound, checked <= the reset path's bound); main alone: the static bound of main's calls, without startup and handlers."
  echo
  [[ -n $breakdown ]] && echo "RAM at 320x240 with 1,000 triangles ($core, phong image): $breakdown." && echo
  # Where one family's renderer flash is (the diffuse Gouraud image: the budget's), by source
  # folder.
  gouraud_elf=$(awk '$1 == "gouraud_diffuse" {print $2}' "$manifest")
  if [[ -n $gouraud_elf ]] && by_folder=$(python3 scripts/flash_by_folder.py "$gouraud_elf" \
       --exclude 'lr::fw::footprint::k' --tool-prefix "$prefix"); then
    echo "Flash of the gouraud_diffuse image by source folder ($core at $opt; without its mesh arrays; scripts/flash_by_folder.py):"
    echo
    echo "$by_folder"
    echo
    if [[ -n $gouraud_split ]]; then
      read -r _ program_bytes program_core <<<"$(awk '$1 == "program"' <<<"$gouraud_split")"
      echo "Of these, the renderer alone: $(group "$(awk '$1 == "renderer" {print $2}' <<<"$gouraud_split")") B; the program: $(group "$program_bytes") B (firmware/, its constants, and of the project's code what only it reaches: ${program_core:-nothing})."
      echo
    fi
  fi
  if [[ $core == *m0plus* ]]; then
    echo "Fit the micro:bit ($(group "$mb_flash") B flash, $(group "$mb_ram") B RAM for data, bss and stack): ${fits[*]:-none}."
    if [[ ${#misfits[@]} -gt 0 ]]; then
      joined=$(printf '%s; ' "${misfits[@]}")
      echo "Not fitting: ${joined%; }."
    fi
    echo
  fi
done

if ((write_docs)); then
  exec 1>&3 3>&-
  cat "$report"
  if [[ $status -eq 0 ]]; then
    grep -v '^footprint: ' "$report" | python3 scripts/write_measurements.py footprint \
      "bash scripts/footprint.sh --write-docs" "Footprint: flash, RAM and stack per configuration" || status=1
  fi
  rm -f "$report"
fi

if [[ $status -ne 0 ]]; then
  echo "footprint: FAILED" >&2
else
  echo "footprint: every check passed (link guard; stack analysis; QEMU runs complete, measured <= static bound; frames identical across cores)."
fi
exit $status
