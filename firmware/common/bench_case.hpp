// What a benchmark image needs besides its scenes (firmware/peer's lr_peer; firmware/bench's
// lr_bench still defines its own copies, so that its counts stay those of the figures measured
// so far: with this header's weak marker its frames count 4 instructions more): the marker the
// instruction-counting plugin counts between (scripts/icount.sh), and the " name value" pairs of
// a case line, which the scripts read by name.
#pragma once

#include <cstdint>
#include <span>

#include "firmware/common/semihost.hpp"

extern "C" {
// Entered right before and right after each measured frame. Its body is one instruction
// (bx lr); noinline + used keep it a real call with a symbol the runner can find.
[[gnu::noinline, gnu::used]] inline void lr_bench_marker() {
  __asm__ volatile("" ::: "memory");
}
}

namespace lr::fw {

struct NamedCount {
  const char* name;
  uint32_t value;
};

// Writes " name value" for each count, in decimal.
inline void write_counts(std::span<const NamedCount> counts) {
  for (const NamedCount& n : counts) {
    semihost::write(" ");
    semihost::write(n.name);
    semihost::write(" ");
    semihost::write_dec(n.value);
  }
}

}  // namespace lr::fw
