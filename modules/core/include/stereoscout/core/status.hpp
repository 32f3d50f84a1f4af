#pragma once
// A status for the tick loop, where nothing throws: a code plus a static message, so
// returning one never allocates.

namespace stereoscout::core {

enum class StatusCode {
  ok,
  invalid_input,   // bad data from a sensor or a log record: skipped and counted
  exhausted,       // a fixed pool or container is full: degraded as documented
  timeout,         // a device did not answer in time
  not_available,   // nothing to read yet (no new frame, no odometry)
  io_error,        // the operating system refused a read or write
};

struct Status {
  StatusCode code = StatusCode::ok;
  const char* message = "";  // static storage only

  static constexpr Status success() { return {}; }
  constexpr bool ok() const { return code == StatusCode::ok; }
};

const char* to_string(StatusCode code);

}  // namespace stereoscout::core
