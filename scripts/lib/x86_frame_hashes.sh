# shellcheck shell=bash
# The x86-64 frames of the pinned scenes as the cross runs compare them (scripts/ci_armhf.sh,
# scripts/ci_aarch64.sh; bash; defines a function only): tests/core/frame_hash_test.cpp of the
# host's debug build, run now from the same sources, writes one "frame hash NAME: rgb ... depth
# ..." line per scene; the ARM builds of the same test then read them (LR_FRAME_HASHES) and fail
# on any difference. No hash is stored in the repository: a deliberate change of the frames needs
# no re-recording, and an ARM frame still has to equal the x86-64 one byte for byte.
#
#   lr_x86_frame_hashes FILE   writes FILE (replacing it); status 0, or 1 with a message
#   LR_HOST_FRAME_HASH_TEST    the host test (default build/debug/tests/core/core_frame_hash_test,
#                              brought up to date first when build/debug is configured)

lr_x86_frame_hashes() {
  local out="$1" exe="${LR_HOST_FRAME_HASH_TEST:-}" log
  if [[ -z "$exe" ]]; then
    exe=build/debug/tests/core/core_frame_hash_test
    if [[ -f build/debug/CMakeCache.txt ]]; then
      cmake --build build/debug --target core_frame_hash_test >/dev/null \
        || { echo "x86 frame hashes: cannot build core_frame_hash_test in build/debug" >&2; return 1; }
    fi
  fi
  if [[ ! -x "$exe" ]]; then
    echo "x86 frame hashes: $exe not built (cmake --preset debug && cmake --build --preset debug --target core_frame_hash_test)" >&2
    return 1
  fi
  mkdir -p "$(dirname "$out")"
  rm -f "$out"
  if ! log="$(LR_FRAME_HASHES_OUT="$out" "$exe" --gtest_filter='FrameHash.*' --gtest_brief=1 2>&1)"; then
    echo "$log" >&2
    echo "x86 frame hashes: $exe failed" >&2
    return 1
  fi
  [[ -s "$out" ]] || { echo "x86 frame hashes: $exe wrote no hashes to $out" >&2; return 1; }
  echo "x86 frame hashes: $(grep -c '^frame hash ' "$out") pinned scenes hashed by $exe ($out)"
}
