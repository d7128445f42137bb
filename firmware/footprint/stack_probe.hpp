// Measures the main stack's high-water mark, to cross-check the static worst case that
// scripts/stack_usage.py computes from the call graph (scripts/footprint.sh asserts measured <=
// static): a static bound below a measured depth would mean the analysis misses something.
//
// The linker script (common/cortex_m_sections.ld) reserves the stack as [_sstack, _estack); the
// reset SP is _estack. paint() fills [_sstack, SP) with a pattern from main itself (inlined: no
// call may put a frame below SP while the loop writes there), high_water() finds the lowest word
// that no longer holds it. Words a function reserves but never writes go unseen, so the figure
// is a lower bound of the real depth, which is what the cross-check needs.
#pragma once

#include <cstdint>

extern "C" {
extern uint32_t _sstack[];  // lowest address of the reserved stack region
extern uint32_t _estack[];  // the reset SP: one past the region's top
}

namespace lr::fw::footprint {

// Not byte-uniform, so that no store of a small constant reproduces it by chance.
inline constexpr uint32_t kStackPaint = 0xC5A3E17Bu;

[[gnu::always_inline]] inline uint32_t* current_sp() {
  uint32_t* sp;
  __asm__ volatile("mov %0, sp" : "=r"(sp));
  return sp;
}

// Paints from the bottom of the stack region up to the caller's SP. Volatile stores: the loop
// must not become a memset call, whose own frame would lie in the area being painted.
[[gnu::always_inline]] inline void paint_stack(uint32_t* sp) {
  for (volatile uint32_t* p = _sstack; p < sp; ++p) *p = kStackPaint;
}

// The lowest address written since paint_stack (== _sstack: the region overflowed, or was
// entirely used).
inline const uint32_t* stack_high_water() {
  const volatile uint32_t* p = _sstack;
  while (p < _estack && *p == kStackPaint) ++p;
  return const_cast<const uint32_t*>(p);
}

// Bytes of stack used below the reset SP.
inline uint32_t stack_depth(const uint32_t* lowest) {
  return static_cast<uint32_t>(reinterpret_cast<uintptr_t>(_estack) -
                               reinterpret_cast<uintptr_t>(lowest));
}

}  // namespace lr::fw::footprint
