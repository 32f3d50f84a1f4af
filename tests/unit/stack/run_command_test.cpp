// `stereoscout run` on a machine without the robot's devices: a clear error naming the device,
// and nothing moves (the GPIO lines open first, so the motors are never enabled).
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "stereoscout/test/command.hpp"
#include "stereoscout/test/paths.hpp"

namespace stereoscout {
namespace {

TEST(RunCommand, WithoutTheRobotNamesTheMissingDeviceAndFails) {
  const std::string config = "/tmp/stereoscout_run_test_" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(config) << "%YAML:1.0\nrobot_pc: {gpio_chip: \"stereoscout_test_no_such_chip\"}\n";
  const test::CommandResult result =
      test::run_stereoscout("run --config " + config + " --max-time 1 --no-log --out /tmp/stereoscout_run_test_out");
  std::remove(config.c_str());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("stereoscout_test_no_such_chip"), std::string::npos) << result.output;
}

TEST(RunCommand, RefusesTheSimulatorsGroundTruth) {
  const test::CommandResult result = test::run_stereoscout("run --localization groundtruth --out /tmp/stereoscout_run_test_out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
}

// Every target's budget profile is a valid config file (check-budgets loads it as one).
TEST(BudgetProfiles, LoadAsConfigFiles) {
  for (const char* target : {"host-x86_64", "robot-aarch64"}) {
    const std::string path = test::source_path(std::string("config/budgets/") + target + ".yaml");
    const test::CommandResult result = test::run_stereoscout("config --config " + path);
    EXPECT_EQ(result.exit_code, 0) << path << "\n" << result.output;
  }
}

}  // namespace
}  // namespace stereoscout
