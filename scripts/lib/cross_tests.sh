# shellcheck shell=bash
# GoogleTest executables of a cross build run under a user-mode emulator (scripts/ci_armhf.sh,
# scripts/ci_aarch64.sh; bash; defines functions only). The executables run directly, not through
# CTest (whose list holds every test of the project, built or not), $(nproc) at a time, each
# with its whole output in BUILD/test-logs/NAME.log and one line saying how it went.
#
#   lr_cross_test_targets BUILD PREFIX...   prints the configured test executables whose names
#                                           start with a PREFIX (core_, hal_, ...): what this
#                                           configuration builds (optional ones included only
#                                           where their libraries were found)
#   lr_cross_tests_run TAG BUILD EMULATOR SYSROOT NAME...
#                                           runs each NAME under EMULATOR -L SYSROOT; status 0
#                                           when every one passed, 1 otherwise

lr_cross_test_targets() {
  local build="$1"
  shift
  local pattern
  pattern="^\\.\\.\\. ($(IFS='|'; echo "$*"))[a-z0-9_]*_test\$"
  cmake --build "$build" --target help | grep -E "$pattern" | sed 's/^\.\.\. //' | sort
}

_lr_cross_run_one() {  # name (LR_CROSS_TAG, LR_CROSS_BUILD, LR_CROSS_EMULATOR, LR_CROSS_SYSROOT)
  local exe log t0 summary
  exe=$(find "$LR_CROSS_BUILD/tests" -name "$1" -type f -perm -u+x | head -n 1)
  log="$LR_CROSS_BUILD/test-logs/$1.log"
  if [ -z "$exe" ]; then
    echo "$LR_CROSS_TAG: FAIL $1: no executable under $LR_CROSS_BUILD/tests"
    return 1
  fi
  t0=$SECONDS
  # (a hung test fails at the timeout, as under CTest)
  if timeout 900 "$LR_CROSS_EMULATOR" -L "$LR_CROSS_SYSROOT" "$exe" --gtest_brief=1 >"$log" 2>&1; then
    summary=$(grep -E '^\[  PASSED  \]' "$log" | tail -n 1 | sed 's/^\[  PASSED  \] //; s/\.$//')
    echo "$LR_CROSS_TAG: PASS $1 (${summary:-?} in $((SECONDS - t0)) s)"
  else
    echo "$LR_CROSS_TAG: FAIL $1 (exit $?; $log):"
    grep -E '^\[  FAILED  \]|Failure|error' "$log" | head -n 20 | sed 's/^/    /'
    return 1
  fi
}

lr_cross_tests_run() {
  export LR_CROSS_TAG="$1" LR_CROSS_BUILD="$2" LR_CROSS_EMULATOR="$3" LR_CROSS_SYSROOT="$4"
  shift 4
  export -f _lr_cross_run_one
  rm -rf "$LR_CROSS_BUILD/test-logs"
  mkdir -p "$LR_CROSS_BUILD/test-logs"
  printf '%s\n' "$@" | xargs -P "$(nproc)" -I{} bash -c '_lr_cross_run_one "$1"' _ {}
}
