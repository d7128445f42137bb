// Status codes returned by every fallible call of the core and the display path.
//
// The renderer's calls out of order, and draws it refuses, each get a code that names the
// problem (docs/api-errors.md: one row per misuse, with the state it leaves).
#pragma once

#include <cstdint>

namespace lr {

enum class Status : uint8_t {
  kOk = 0,
  kInvalidArgument,  // a parameter outside its documented range
  kCapacity,         // a caller-provided store was full: work was dropped and counted
  kDisplayError,     // the display backend reported a failed transfer
  kTimeout,          // a bounded wait for the display expired
  kBusy,             // the call is not allowed now (e.g. a sink call outside its frame)
  kNotConfigured,    // a renderer call before a successful configure()
  kNoFrame,          // draw or render with no frame begun since configure(): begin_frame() first
  kFrameRendered,    // draw or render after render(): the frame is over, begin_frame() first
  kMissingStore,     // the draw needs a FrameStorage store that was not given (size 0)
  kStoreTooSmall,    // configure(): a store is smaller than the viewport or its partner store needs
  kNotLinked,        // the renderer's SpanSet links no span routine for the draw's state
};

constexpr const char* to_string(Status s) {
  switch (s) {
    case Status::kOk:
      return "ok";
    case Status::kInvalidArgument:
      return "invalid argument";
    case Status::kCapacity:
      return "capacity exceeded";
    case Status::kDisplayError:
      return "display error";
    case Status::kTimeout:
      return "timeout";
    case Status::kBusy:
      return "busy";
    case Status::kNotConfigured:
      return "not configured (configure() first)";
    case Status::kNoFrame:
      return "no frame begun (begin_frame() first)";
    case Status::kFrameRendered:
      return "frame already rendered (begin_frame() first)";
    case Status::kMissingStore:
      return "a store the draw needs is missing (FrameStorage)";
    case Status::kStoreTooSmall:
      return "a store is smaller than configure() needs (FrameStorage)";
    case Status::kNotLinked:
      return "draw state not linked (outside the renderer's SpanSet)";
  }
  return "unknown";
}

}  // namespace lr
