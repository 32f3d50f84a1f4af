// The stereoscout command as a user runs it: exit codes and messages.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "stereoscout/test/command.hpp"

namespace {

using stereoscout::test::CommandResult;

CommandResult run(const std::string& arguments) { return stereoscout::test::run_stereoscout(arguments); }

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, HelpListsCommands) {
  const CommandResult result = run("--help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("config"), std::string::npos);
}

TEST(Cli, UnknownCommandFailsClearly) {
  const CommandResult result = run("fly");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("unknown command 'fly'"), std::string::npos);
}

TEST(Cli, ConfigAcceptsTheDefaultFile) {
  const CommandResult result = run("config");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("config OK"), std::string::npos);
}

TEST(Cli, ConfigReportsEveryProblemWithFileAndKey) {
  const std::string path = write_temp("bad.yaml", "filter:\n  particles: lots\nrobot:\n  radius: 0.3\n");
  const CommandResult result = run("config --config " + path);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find(path + ": filter.particles: expected an integer"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find(path + ": robot.radius: unknown key (did you mean 'radius_m'?)"), std::string::npos)
      << result.output;
}

TEST(Cli, ConfigPrintRoundTrips) {
  const CommandResult printed = run("config --print");
  ASSERT_EQ(printed.exit_code, 0);
  const std::string path = write_temp("printed.yaml", printed.output);
  EXPECT_EQ(run("config --config " + path).exit_code, 0);
}

TEST(Cli, BadOptionsAreNamed) {
  CommandResult result = run("config --frobnicate");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("unknown option --frobnicate"), std::string::npos);
  result = run("config --config");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("--config needs a value"), std::string::npos);
  result = run("config --help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("usage: stereoscout config"), std::string::npos);
}

}  // namespace
