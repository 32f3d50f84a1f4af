#pragma once
// What `explore`, `replay` and `run` share: the config with the command-line overrides, the
// simulated world, the log writer's options and the end of a run (run directory + summary).

#include <string>

#include "arguments.hpp"
#include "run_directory.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/log/writer.hpp"
#include "stereoscout/stack/stack.hpp"

namespace stereoscout::cli {

// How long start-up waits for the first odometry reading before it gives up (a base link
// that is not talking; the simulator's first reading comes after 0.19 s).
inline constexpr double kStartTimeoutS = 5.0;

struct RunSetup {
  core::SystemConfig config;
  stack::StackOptions options;
  host_sim::World world;
};

// Loads --config and applies --seed, --particles, --max-time, --localization and --world
// (those the command declared). False, message printed, on a bad file or value.
bool load_run_setup(const Arguments& arguments, const char* command, RunSetup& setup);
// Stack options from the config's run section (localization, time limit).
bool stack_options_from(const core::SystemConfig& config, const char* command, stack::StackOptions& options);
// Loads run.world (resolved against the install and source trees) into setup.world and
// stores the resolved path in the config, so that the logged config names a file a replay
// can find. False, message printed, on failure.
bool load_world_of(core::SystemConfig& config, const char* command, RunSetup& setup);

log::LogWriterOptions log_writer_options(const core::SystemConfig& config, bool wait_when_full);

// Writes the run directory and prints one summary line naming the map and the report.
int finish_run(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
               const std::string& out, const char* command);

}  // namespace stereoscout::cli
