// The renderer's second, optional output port: each strip's depth buffer, for tools (the CLI's
// depth images, tests of the depth test).
#pragma once

#include <cstdint>
#include <span>

#include "lineraster/core/output/strip_sink.hpp"

namespace lr {

// Receives each strip's depth buffer (16-bit, 65535 = far/cleared), rows packed as the strip's.
class DepthSink {
 public:
  virtual void on_depth(const StripRect& rect, std::span<const uint16_t> depth) = 0;

 protected:
  ~DepthSink() = default;
};

}  // namespace lr
