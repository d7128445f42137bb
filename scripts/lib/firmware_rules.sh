# shellcheck shell=bash disable=SC2034  # sourced: the variables are used by the scripts that source it
# What a linked bare-metal image may not contain: the one list of the link guard, sourced by
# scripts/ci_cross.sh and scripts/footprint.sh (bash; defines variables and functions only).
#
# The core and the firmware run without a heap, without exceptions and without floating point
# (integers only, so that frames are the same on every core). The compiler flags make most
# violations impossible to write, but a stray library call or a float expression still links:
# libgcc supplies soft-float helpers, and on a core with an FPU the compiler emits VFP
# instructions inline. So every image is checked after linking, by its symbols and, on cores
# with an FPU, by its instructions.
#
#   lr_fw_guard ELF           prints one line per violation; status 0 clean, 1 violations,
#                             2 the ELF could not be read
#   lr_fw_guard_what          what the guard checks, for the scripts' summary lines
#   LR_FW_TOOL_PREFIX         binutils prefix (default arm-none-eabi-)

# Heap and exception support, defined or referenced (nm types T, W, U, ...):
#   malloc family, newlib's reentrant variants and the heap's sbrk;
#   operator new/delete in every form (_Znw*, _Zna*, _ZdlPv*, _ZdaPv*);
#   the C++ ABI runtime (__cxa_*: exception allocation and throwing, guards of function-local
#   statics, atexit), the personality routines and the unwinder.
lr_fw_heap_exceptions_re='^(malloc|free|calloc|realloc|memalign|aligned_alloc|posix_memalign|valloc|pvalloc|_sbrk|sbrk|_sbrk_r|_malloc_r|_free_r|_calloc_r|_realloc_r|_memalign_r|_Znw.*|_Zna.*|_ZdlPv.*|_ZdaPv.*|__cxa_.*|__gxx_personality_.*|__aeabi_unwind_cpp_pr.*|_Unwind_.*)$'

# Defined by firmware/common/startup.cpp so that libsupc++'s versions (which bring
# std::terminate, the demangler and malloc) are never linked.
lr_fw_allowed_re='^(__cxa_pure_virtual|__cxa_deleted_virtual)$'

# Software floating point (libgcc): the Arm EABI helpers and the generic libgcc names, single,
# double and wider, arithmetic, comparisons and conversions. Integer helpers (__aeabi_idiv,
# __aeabi_ldivmod, __aeabi_lmul, __aeabi_llsl, ...) are not matched.
lr_fw_soft_float_re='^(__aeabi_[fd](add|sub|rsub|mul|div|rdiv|neg|cmp[a-z]*|2[a-z0-9]+)|__aeabi_c[fd]r?cmp[a-z]*|__aeabi_u?[il]2[fd]|__aeabi_[fdh]2[fdh]|__(add|sub|mul|div|neg)[sdtx]f[23]|__(extend|trunc)[a-z]+f2|__fix(uns)?[sdtx]f[sdt]i|__float(un)?[sdt]i[sdtx]f|__(eq|ne|lt|le|gt|ge|unord|cmp)[sdtx]f2|__powi[sdtx]f2|__(mul|div)[sdtx]c3)$'

# VFP data-processing instructions, as arm-none-eabi-objdump -d prints them (condition code and
# type suffix: vmul.f32, vcvt.s32.f32, vcmpe.f64, vseleq.f32, ...). Loads, stores and vmov are
# not arithmetic: with -mfloat-abi=hard the compiler may keep integers in FP registers.
lr_fw_vfp_arith_re='^v(add|sub|mul|nmul|div|mla|mls|nmla|nmls|fma|fms|fnma|fnms|sqrt|abs|neg|cvt[a-z]*|cmpe?|rint[a-z]*|maxnm|minnm|sel[a-z]*)(eq|ne|cs|cc|hs|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)?\.'

# Code allowed to use the FPU, "image-name-glob function-name-ERE" per line: the fault checks'
# main() runs one FPU multiply on purpose, proving that Reset_Handler enabled the FPU
# (firmware/fault_check/main.cpp).
lr_fw_fpu_allowed=(
  'lr_fault_* ^main$'
)

lr_fw_guard_what="no heap, no exceptions or unwinder, no soft-float helpers, no FPU arithmetic"

# lr_fw_fpu_allowed_in IMAGE-NAME: prints the function ERE allowed to use the FPU in that image
# (the alternatives of every matching entry), or nothing.
lr_fw_fpu_allowed_in() {
  local image="$1" entry glob re out=""
  for entry in "${lr_fw_fpu_allowed[@]}"; do
    glob="${entry%% *}" re="${entry#* }"
    # shellcheck disable=SC2053  # the glob is meant to match
    [[ "$image" == $glob ]] && out+="${out:+|}(${re})"
  done
  printf '%s' "$out"
}

lr_fw_guard() {
  local elf="$1" prefix="${LR_FW_TOOL_PREFIX:-arm-none-eabi-}" syms names image disasm
  local status=0 line
  syms="$("${prefix}nm" "$elf" 2>/dev/null)" || { echo "cannot read the symbols of $elf"; return 2; }
  # nm lines: "<address> <type> <name>" or "         U <name>": the name is the last field.
  names="$(awk '{print $NF}' <<<"$syms" | sort -u)"
  while IFS= read -r line; do
    if [[ -n "$line" ]]; then echo "heap or exception support: $line"; status=1; fi
  done < <(grep -E "$lr_fw_heap_exceptions_re" <<<"$names" | grep -vE "$lr_fw_allowed_re")
  while IFS= read -r line; do
    if [[ -n "$line" ]]; then echo "soft-float helper: $line"; status=1; fi
  done < <(grep -E "$lr_fw_soft_float_re" <<<"$names")

  # FPU arithmetic, per function. Only images built for an FPU can hold any (the build
  # attributes say so); the others are not disassembled.
  if "${prefix}readelf" -A "$elf" 2>/dev/null | grep -q 'Tag_FP_arch:'; then
    image="$(basename "$elf" .elf)"
    disasm="$("${prefix}objdump" -d --no-show-raw-insn "$elf" 2>/dev/null)" ||
      { echo "cannot disassemble $elf"; return 2; }
    # Regular expressions through the environment: awk -v would interpret their backslashes.
    while IFS= read -r line; do
      if [[ -n "$line" ]]; then echo "FPU arithmetic in $line"; status=1; fi
    done < <(LR_INSN_RE="$lr_fw_vfp_arith_re" LR_ALLOWED_RE="$(lr_fw_fpu_allowed_in "$image")" \
      awk -F'\t' '
        BEGIN { insn_re = ENVIRON["LR_INSN_RE"]; allowed_re = ENVIRON["LR_ALLOWED_RE"] }
        /^[0-9a-f]+ <.*>:$/ { fn = $0; sub(/^[^<]*</, "", fn); sub(/>:$/, "", fn); next }
        NF >= 2 && $2 ~ insn_re && !(allowed_re != "" && fn ~ allowed_re) {
          if (!(fn in n)) { at = $1; gsub(/[ :]/, "", at); first[fn] = $2 " " $3 " at 0x" at }
          n[fn]++
        }
        END { for (f in n) printf "%s: %d instruction(s), the first: %s\n", f, n[f], first[f] }' \
        <<<"$disasm" | sort)
  fi
  return $status
}

# Calls through pointers in the images, for scripts/stack_usage.py (its --indirect-from rules;
# shared by scripts/footprint.sh, ci_firmware.sh and small_ram.sh): the renderer calls the
# sink's virtual methods and each triangle's row loop; the textured and Phong row loop calls
# the span routines of its families; textured and Phong spans call texel fetchers; the front
# end calls the renderer's admission test and the routines of its FrontEndRoutines (Phong
# records, flat shading's face lighting, triangles' own colours, point lighting, vertex
# attributes, the checks, stores and record fields of textured and Phong draws' maps, a
# one-coloured draw's colour, the clipper with or without them: those of the renderer's span
# set; the lighting's preparation (whole, or diffuse only); bands (with the draw's record for them), the vertex cache, two-sided lighting's clipped
# back-face test, strip signatures and the per-vertex lighting with or without specular and the
# world-space path: those of its RendererFeatures), and draw_screen's binning when it
# replays a band; the panel path (the Cortex-M7 demo) calls its bus; Reset_Handler calls the
# static constructors (none: the images constant-initialise).
lr_fw_stack_rules=(
  --indirect-from 'lr::(Renderer|StripLoop)<.*>::(render|render_bands|strips(<[^>]*>)?|crowded_strip)\('
  'OrderedStripSink<.*>::|lr::PanelSink::|lr::StripSink<.*>::(retains_frame|keep)\(|lr::(lanes_rows|untextured_rows_per_span|legacy_rows)<'
  --indirect-from 'lr::legacy_rows<' 'lr::fill_tex_span<|lr::fill_phong_span<'
  --indirect-from 'lr::untextured_rows_walk<' 'lr::untextured_span_call<'
  --indirect-from 'lr::(detail::)?fill_(tex_span_body|tex_span|phong_span)<' 'lr::fetch_batch<'
  --indirect-from '^Reset_Handler$' '^_GLOBAL__sub_I_'
  --indirect-from 'lr::FrontEnd::(draw(_screen)?|admitted)\(' 'lr::admits<|lr::DrawRecords::phong_record\('
  --indirect-from 'lr::FrontEnd::(general_triangles<[^>]*>|triangle_loop|run_mesh)\(' 'lr::VertexStage::light_face(<[^>]*>)?\('
  --indirect-from 'lr::FrontEndParts::flat_colors\(|lr::MeshDraw::flat_colors\(' 'lr::VertexStage::light_face(<[^>]*>)?\('
  --indirect-from 'lr::FrontEnd::(general_triangles<[^>]*>|light_corners|light_other|light_list|triangle_loop|run_mesh)\(|lr::MeshDraw::light_vertex\(' 'lr::VertexStage::light<'
  --indirect-from 'lr::FrontEnd::general_triangles<[^>]*>\(' 'lr::FrontEndParts::flat_colors\('
  --indirect-from 'plan_draw\(|lr::FrontEnd::(draw|replay)\(' 'lr::FrontEndParts::check_maps\('
  --indirect-from 'lr::FrontEnd::(draw|draw_screen)\(' 'lr::FrontEndParts::(maps_store_missing|one_color)\(|lr::DrawRecords::texture_fields\('
  --indirect-from 'lr::FrontEnd::(draw|replay)\(' 'lr::prepare(_diffuse)?_lighting\('
  --indirect-from 'lr::FrontEnd::run_mesh\(|lr::VertexStage::object_lights\(' 'lr::prepare(_diffuse)?_object_lights\('
  --indirect-from 'lr::FrontEnd::draw\(' 'lr::FrontEndParts::record_call\('
  --indirect-from 'lr::VertexStage::(light|light_face)(<[^>]*>)?\(' 'lr::light_point_at\('
  --indirect-from 'lr::VertexStage::transform_range\(' 'lr::VertexStage::attributes\('
  --indirect-from 'lr::VertexStage::VertexStage\(' 'lr::fine_model_view_projection\('
  --indirect-from 'lr::FrontEnd::replay\(' 'lr::FrontEnd::(replay_screen|run_screen)\('
  --indirect-from 'lr::FrontEnd::bin\(' 'lr::FrontEndParts::(shrink_band|sign_triangle)\(|lr::VertexStore::persist\('
  --indirect-from 'lr::FrontEnd::begin_frame\(' 'lr::FrontEndParts::sign_frame\('
  --indirect-from 'lr::FrontEnd::draw(_screen)?\(' 'lr::FrontEndParts::sign_draw\('
  --indirect-from 'lr::FrontEnd::general_triangles<[^>]*>\(' 'lr::VertexStore::cache_corners\(|lr::front_facing_clip\(|lr::FrontEndParts::polygon_outside_band\('
  --indirect-from 'lr::FrontEnd::triangle_loop\(' 'lr::FrontEndParts::triangles<'
  --indirect-from 'lr::FrontEnd::(general_triangles<[^>]*>|clip_and_bin)\(' 'lr::clip_polygon<'
  --indirect-from 'lr::FrontEnd::run_(mesh|screen)\(' 'lr::VertexStore::begin_cache\(|lr::FrontEndParts::compact_vertices\('
  --indirect-from 'lr::(PanelSink|Panel|fw::demo::PanelOutput<.*>)::|lr::(send_commands?|write_window)\(' 'lr::fw::PpmPanelBus<.*>::|lr::PanelBus::'
)
