// The Cortex-M7's L1 data cache through its system control block registers (ARMv7-M
// Architecture Reference Manual, "Cache maintenance operations"; what CMSIS's SCB_EnableDCache
// and SCB_CleanDCache_by_Addr do). A board's startup turns the cache on; its DMA bus cleans the
// bytes a DMA engine is about to read (lr::PanelBus::clean_dcache, docs/dma.md).
//
// Only for cores that have the cache (Cortex-M7): on the others these addresses are reserved.
// QEMU models no cache: there the writes are accepted and change nothing, so a frame under QEMU
// shows that the calls are made with the right ranges, not that the cache was needed.
#pragma once

#include <cstdint>
#include <span>

namespace lr::fw::m7 {

// The M7's data-cache line, bytes: the granule of every operation below.
inline constexpr uint32_t kDcacheLine = 32;

namespace detail {
inline volatile uint32_t& scb(uint32_t address) {
  return *reinterpret_cast<volatile uint32_t*>(address);
}
inline constexpr uint32_t kCcr = 0xE000ED14;      // configuration and control; bit 16: DC
inline constexpr uint32_t kCcsidr = 0xE000ED80;   // size of the cache CSSELR selects
inline constexpr uint32_t kCsselr = 0xE000ED84;   // 0: the L1 data cache
inline constexpr uint32_t kDcisw = 0xE000EF60;    // invalidate by set and way
inline constexpr uint32_t kDccmvac = 0xE000EF68;  // clean by address, to the point of coherency
inline constexpr uint32_t kCcrDc = 1u << 16;
inline void barriers() {
  asm volatile("dsb 0xF\n isb 0xF" ::: "memory");
}
}  // namespace detail

// Invalidates the whole data cache (its power-on contents are undefined), then enables it.
inline void enable_dcache() {
  using namespace detail;
  scb(kCsselr) = 0;
  barriers();
  const uint32_t ccsidr = scb(kCcsidr);
  const uint32_t sets = ((ccsidr >> 13) & 0x7FFFu) + 1, ways = ((ccsidr >> 3) & 0x3FFu) + 1;
  // DCISW: the set above the line offset (log2 of 32 B = 5), the way in the top bits.
  const uint32_t way_shift = ways > 1 ? static_cast<uint32_t>(__builtin_clz(ways - 1)) : 0;
  for (uint32_t set = 0; set < sets; ++set)
    for (uint32_t way = 0; way < ways; ++way)
      scb(kDcisw) = (set << 5) | (way << way_shift);  // one way: way is 0
  asm volatile("dsb 0xF" ::: "memory");
  scb(kCcr) = scb(kCcr) | kCcrDc;
  barriers();
}

// Writes back every line that holds a byte of `bytes` (whole lines: docs/dma.md says why the
// strip buffers own theirs). Returns the number of lines cleaned.
inline uint32_t clean_dcache(std::span<const uint8_t> bytes) {
  if (bytes.empty()) return 0;
  const uint32_t begin = reinterpret_cast<uintptr_t>(bytes.data()) & ~(kDcacheLine - 1);
  const uint32_t end = static_cast<uint32_t>(reinterpret_cast<uintptr_t>(bytes.data())) +
                       static_cast<uint32_t>(bytes.size());
  asm volatile("dsb 0xF" ::: "memory");  // the CPU's last writes reach the cache first
  uint32_t lines = 0;
  for (uint32_t a = begin; a < end; a += kDcacheLine, ++lines) detail::scb(detail::kDccmvac) = a;
  detail::barriers();
  return lines;
}

}  // namespace lr::fw::m7
