// stereoscout replay: the whole stack on a recorded sensor log, on a virtual clock.

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "arguments.hpp"
#include "boards.hpp"
#include "commands.hpp"
#include "run_directory.hpp"
#include "run_loop.hpp"
#include "run_setup.hpp"
#include "stereoscout/report/wall_stopwatch.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kName = "stereoscout replay";

// The configuration the live run used, from the log's config record.
bool config_from_log(host_replay::LogReplay& replay, const std::string& log_path, RunSetup& setup) {
  if (replay.config_yaml().empty()) {
    std::fprintf(stderr, "%s: %s: no config record: not a stereoscout run log, or its start is damaged\n", kName,
                 log_path.c_str());
    return false;
  }
  const core::SystemConfigLoad load = core::load_system_config_text(replay.config_yaml(), log_path + " (config record)");
  if (!load.ok()) {
    std::fprintf(stderr, "%s: config problem(s):\n%s", kName, load.error_text().c_str());
    return false;
  }
  setup.config = load.config;
  return stack_options_from(setup.config, kName, setup.options);
}

void add_damage_counts(host_replay::LogReplay& replay, RunContext& context) {
  const log::LogReaderStats& reader = replay.reader_stats();
  const host_replay::LogReplayStats& stats = replay.stats();
  context.extra_numbers = {
      {"log_records_read", static_cast<double>(reader.records)},
      {"log_damaged_places", static_cast<double>(reader.damaged)},
      {"log_bytes_skipped", static_cast<double>(reader.bytes_skipped)},
      {"log_truncated_bytes", static_cast<double>(reader.truncated_bytes)},
      {"log_unknown_records", static_cast<double>(reader.unknown_types)},
      {"log_invalid_records", static_cast<double>(stats.invalid_records)},
      {"log_end_of_run_seen", replay.saw_end_of_run() ? 1.0 : 0.0},
  };
}

}  // namespace

int run_replay(int argc, char** argv) {
  Arguments arguments("replay",
                      "Re-runs the whole stack on a sensor log recorded by `explore` or `run`, on a virtual clock,\n"
                      "with the configuration and seed recorded in the log. The run directory it writes is byte\n"
                      "for byte the live run's (report.json aside: wall times differ). Damaged records and a\n"
                      "truncated end are skipped and counted in report.json.");
  arguments.positional("LOG", "the sensors.log of a run directory");
  arguments.option("out", "DIR", "run directory (created)", "runs/replay");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  const auto wall_start = std::chrono::steady_clock::now();
  const std::string log_path = arguments.get("LOG");
  // The frame size is only known from the config record: read it first with a probe.
  RunSetup setup;
  {
    host_replay::LogReplay probe{host_replay::LogReplayOptions{}};
    std::string error;
    if (!probe.open(log_path, error)) {
      std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
      return 1;
    }
    if (!config_from_log(probe, log_path, setup)) return 1;
  }
  host_replay::LogReplayOptions replay_options;
  replay_options.width_px = setup.config.camera.width_px;
  replay_options.height_px = setup.config.camera.height_px;
  replay_options.max_payload_bytes = log_writer_options(setup.config, false).max_payload_bytes + 1024;
  ReplayBoard board(replay_options);
  std::string error;
  if (!board.open(log_path, error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  RunContext context;
  const bool has_world = std::filesystem::exists(setup.config.run.world) && load_world_of(setup.config, kName, setup);
  if (has_world) {
    context.world_name = setup.world.name;
    context.world = &setup.world;
  }
  const std::string out = arguments.get("out");
  std::error_code ignored;
  std::filesystem::create_directories(out, ignored);

  report::WallStopwatch stopwatch;
  stack::Stack stack(setup.config, setup.options, board.board(), stopwatch);
  if (!stack.start(kStartTimeoutS, error)) {
    std::fprintf(stderr, "%s: %s: %s\n", kName, log_path.c_str(), error.c_str());
    return 1;
  }
  host_replay::LogReplay& replay = board.replay();
  LoopHooks hooks;
  // The live run's last tick is the end_of_run record's time; a cut log ends where it ends.
  hooks.should_stop = [&] {
    if (replay.saw_end_of_run()) return stack.now_ns() >= replay.end_of_run_ns();
    return replay.finished();
  };
  run_to_end(stack, hooks);
  stack.finish();

  context.command = "replay";
  context.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  add_damage_counts(replay, context);
  const log::LogReaderStats& reader = replay.reader_stats();
  if (reader.damaged > 0 || reader.truncated_bytes > 0 || replay.stats().invalid_records > 0) {
    std::fprintf(stderr, "%s: %s: %llu damaged place(s), %llu bytes truncated, %llu invalid record(s) skipped\n", kName,
                 log_path.c_str(), static_cast<unsigned long long>(reader.damaged),
                 static_cast<unsigned long long>(reader.truncated_bytes),
                 static_cast<unsigned long long>(replay.stats().invalid_records));
  }
  return finish_run(stack, setup.config, context, out, kName);
}

}  // namespace stereoscout::cli
