// Status codes returned by every fallible call of the core and the display path.
#pragma once

#include <cstdint>

namespace lr {

enum class Status : uint8_t {
  kOk = 0,
  kInvalidArgument,  // a parameter outside its documented range
  kCapacity,         // a caller-provided store was full: work was dropped and counted
  kDisplayError,     // the display backend reported a failed transfer
  kTimeout,          // a bounded wait for the display expired
  kBusy,             // the call is not allowed now (e.g. draw after render started)
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
  }
  return "unknown";
}

}  // namespace lr
