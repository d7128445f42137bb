#!/bin/bash
# Builds the libFuzzer targets with clang (tests/fuzz/CMakeLists.txt, its own project, in
# build/fuzz: ASan + UBSan + coverage), replays every committed input (tests/fuzz/corpus/<target>/
# seeds and tests/fuzz/regressions/<target>/ crash inputs), then fuzzes each target for the given
# time. The working corpus grows in build/fuzz/corpus/<target>/ and is kept between runs.
# A crash (or a broken invariant, or a timeout or out-of-memory) is copied to
# tests/fuzz/regressions/<target>/ (commit it: the main build's lr_fuzz_regression_test replays it
# with g++) and the script fails.
# Usage: scripts/fuzz.sh [seconds per target, default 60] [target ...]   (obj, png, pipeline)
#        scripts/fuzz.sh --ci [target ...]: a fixed number of runs from a fixed seed and a fresh
#        working corpus: nearly the same inputs on every run (libFuzzer
#        is not bit-for-bit repeatable), so CI rarely passes or fails by luck; open-ended
#        exploration is the timed form above.
# Needs clang and libclang-rt-14-dev (scripts/setup.sh test installs them).
set -euo pipefail
cd "$(dirname "$0")/.."
ci=0
if [ "${1:-}" = --ci ]; then
  ci=1
  secs=0
else
  secs=${1:-60}
fi
shift || true
declare -A ci_runs=([obj]=150000 [png]=200000 [pipeline]=20000)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(pipeline obj png)
jobs=$(nproc)

CC=clang CXX=clang++ cmake -S tests/fuzz -B build/fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build/fuzz -j"$jobs" --target "${targets[@]/#/lr_fuzz_}"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}
# One target: replay, then fuzz. Prints to stdout; returns non-zero on a failure.
fuzz_one() {
  local t=$1 result=0
  exe=build/fuzz/lr_fuzz_$t
  seeds=tests/fuzz/corpus/$t
  regressions=tests/fuzz/regressions/$t
  work=build/fuzz/corpus/$t
  artifacts=build/fuzz/artifacts/$t
  mkdir -p "$work" "$artifacts" "$regressions"

  echo "== fuzz $t: replay of seeds and regressions"
  mapfile -t replay < <(find "$seeds" "$regressions" -type f ! -name '.*' ! -name 'README*' | sort)
  if [ ${#replay[@]} -gt 0 ]; then
    if ! "$exe" -timeout=10 "${replay[@]}" >"$artifacts/replay.log" 2>&1; then
      tail -n 40 "$artifacts/replay.log"
      echo "fuzz $t: a committed input fails (log: $artifacts/replay.log)" >&2
      return 1
    fi
    echo "${#replay[@]} inputs replayed"
  fi

  log=$artifacts/fuzz.log
  if [ $ci -eq 1 ]; then
    echo "== fuzz $t: ${ci_runs[$t]} runs from seed 1"
    work=build/fuzz/corpus-ci/$t
    rm -rf "$work"
    mkdir -p "$work"
    budget=(-runs="${ci_runs[$t]}" -seed=1)
  else
    echo "== fuzz $t: ${secs} s"
    budget=(-max_total_time="$secs")
  fi
  set +e
  "$exe" "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "$work" "$seeds" >"$log" 2>&1
  rc=$?
  set -e
  grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)' "$log" | tail -n 2 || true
  grep -E 'stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' "$log" || true
  if [ $rc -ne 0 ]; then
    result=1
    tail -n 60 "$log"
    for a in "$artifacts"/crash-* "$artifacts"/leak-* "$artifacts"/timeout-* "$artifacts"/oom-* \
             "$artifacts"/slow-unit-*; do
      [ -f "$a" ] || continue
      cp "$a" "$regressions/"
      echo "fuzz $t: new regression input $regressions/$(basename "$a") (commit it)" >&2
      rm -f "$a"
    done
  fi
  return $result
}

# The targets run side by side, nproc at a time (the slowest, pipeline, starts first by
# default); each report is printed whole, in the order given, when all are done.
failed=0
reports=build/fuzz/reports
rm -rf "$reports"
mkdir -p "$reports"
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  (if fuzz_one "$t" >"$reports/$t.txt" 2>&1; then echo 0; else echo 1; fi >"$reports/$t.status") &
done
wait
for t in "${targets[@]}"; do
  cat "$reports/$t.txt"
  [ "$(cat "$reports/$t.status" 2>/dev/null)" = 0 ] || failed=1
done
if [ $failed -ne 0 ]; then
  echo "fuzz: FAILED (inputs in tests/fuzz/regressions/; reproduce: build/fuzz/lr_fuzz_<target> FILE)" >&2
  exit 1
fi
echo "== fuzz: no crash"
