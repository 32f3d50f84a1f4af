#pragma once
// Runs the stereoscout executable as a user would, for tests of the command line: exit code
// and everything it printed. In a cross build it runs under the same emulator as the tests.
// A test target gets the executable's path with stereoscout_test_runs_command(<target>).

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace stereoscout::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline CommandResult run_stereoscout(const std::string& arguments) {
  const std::string emulator = STEREOSCOUT_TEST_BINARY_EMULATOR;
  const std::string command =
      (emulator.empty() ? "" : emulator + " ") + STEREOSCOUT_TEST_BINARY + " " + arguments + " 2>&1";
  CommandResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    return result;
  }
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) {
    result.output += buffer;
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace stereoscout::test
