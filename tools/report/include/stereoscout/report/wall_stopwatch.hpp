#pragma once
// The wall clock as a core::TimeSource, for timing stages in reports (host tools only: what
// the stack computes never depends on it).
#include <chrono>

#include "stereoscout/core/logging.hpp"

namespace stereoscout::report {

class WallStopwatch final : public core::TimeSource {
 public:
  std::int64_t now_ns() const override {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
};

}  // namespace stereoscout::report
