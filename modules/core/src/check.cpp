#include "stereoscout/core/check.hpp"

#include <cstdio>
#include <cstdlib>

#include "stereoscout/core/status.hpp"

namespace stereoscout::core {

void check_failed(const char* file, int line, const char* condition, const char* message) {
  std::fprintf(stderr, "%s:%d: check failed: %s (%s)\n", file, line, message, condition);
  std::fflush(stderr);
  std::abort();
}

const char* to_string(StatusCode code) {
  switch (code) {
    case StatusCode::ok: return "ok";
    case StatusCode::invalid_input: return "invalid input";
    case StatusCode::exhausted: return "exhausted";
    case StatusCode::timeout: return "timeout";
    case StatusCode::not_available: return "not available";
    case StatusCode::io_error: return "i/o error";
  }
  return "?";
}

}  // namespace stereoscout::core
