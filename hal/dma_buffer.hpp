// Strip buffers for a bus that sends them by DMA: each starts on a data-cache line and ends on
// one, so the cache maintenance of one buffer (PanelBus::clean_dcache, done by whole lines)
// never writes back or discards anything else. Give two of them to a PanelSink.
//
//   lr::DmaStripBuffer<240 * 8> strip0, strip1;   // in .bss, or a DMA-capable section
//   lr::PanelSink sink(panel, strip0.pixels(), strip1.pixels(), signatures, timeout_ms);
//
// LR_DMA_ALIGNMENT sets the line (bytes, a power of two): 32 by default, the Cortex-M7's L1
// data-cache line; a board with a longer line or a stricter DMA defines it for every file that
// includes this header (its firmware's compile definitions).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "lineraster/core/output/pixel_format.hpp"

#ifndef LR_DMA_ALIGNMENT
#define LR_DMA_ALIGNMENT 32
#endif

namespace lr {

// Alignment and size granule of DMA strip buffers, bytes.
inline constexpr size_t kDmaAlignment = LR_DMA_ALIGNMENT;
static_assert(kDmaAlignment >= alignof(uint32_t) && (kDmaAlignment & (kDmaAlignment - 1)) == 0,
              "LR_DMA_ALIGNMENT must be a power of two of at least 4 bytes");

// `bytes` rounded up to whole lines.
constexpr size_t dma_padded(size_t bytes) {
  return (bytes + kDmaAlignment - 1) / kDmaAlignment * kDmaAlignment;
}

// One strip buffer of `Pixels` RGB565 pixels (wire order), aligned and padded to whole lines.
template <size_t Pixels>
struct alignas(kDmaAlignment) DmaStripBuffer {
  using Pixel = Rgb565Be::Storage;
  static constexpr size_t kPixels = Pixels;
  static constexpr size_t kBytes = dma_padded(Pixels * sizeof(Pixel));
  static_assert(Pixels > 0 && kBytes % sizeof(Pixel) == 0);

  std::array<Pixel, kBytes / sizeof(Pixel)> storage{};

  // The strip's pixels (the padding is not lent out).
  std::span<Pixel> pixels() { return {storage.data(), Pixels}; }
};

}  // namespace lr
