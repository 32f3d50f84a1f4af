// stereoscout check-budgets: a run's report.json against a target's budget profile.
//
// A budget profile (config/budgets/<target>.yaml) is a config file holding only the
// `budgets` section: per task the rate and the worst-case time allowed on that target. A run
// keeps its budgets when every task's p99 run time is within its budget (so at most 1% of
// runs overran) and no never-skip task missed a period.

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "arguments.hpp"
#include "commands.hpp"
#include "stereoscout/core/system_config.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kName = "stereoscout check-budgets";

struct TaskTiming {
  long long runs = -1;
  long long p99_us = -1;
  long long max_us = -1;
  long long overruns = -1;
  long long missed_periods = -1;
};

// Reads the "timing" object of a report written by report::JsonWriter (one key per line).
bool read_timing(const std::string& path, std::map<std::string, TaskTiming>& timing, std::string& error) {
  std::ifstream file(path);
  if (!file) {
    error = path + ": cannot open";
    return false;
  }
  std::string line;
  bool inside = false;
  std::string task;
  while (std::getline(file, line)) {
    const std::size_t quote = line.find('"');
    const std::size_t end = quote == std::string::npos ? std::string::npos : line.find('"', quote + 1);
    const std::string key = end == std::string::npos ? "" : line.substr(quote + 1, end - quote - 1);
    if (!inside) {
      inside = key == "timing";
      continue;
    }
    if (line.find('{') != std::string::npos) {
      task = key;
    } else if (line.find('}') != std::string::npos) {
      if (task.empty()) break;  // end of "timing"
      task.clear();
    } else if (!task.empty() && end != std::string::npos) {
      const long long value = std::atoll(line.c_str() + end + 2);
      TaskTiming& t = timing[task];
      if (key == "runs") t.runs = value;
      if (key == "p99_us") t.p99_us = value;
      if (key == "max_us") t.max_us = value;
      if (key == "overruns") t.overruns = value;
      if (key == "missed_periods") t.missed_periods = value;
    }
  }
  if (timing.empty()) error = path + ": no \"timing\" object (not a stereoscout report.json?)";
  return !timing.empty();
}

bool never_skipped(const std::string& task) {
  return task == "safety" || task == "capture" || task == "odometry" || task == "drive" || task == "logging";
}

}  // namespace

int run_check_budgets(int argc, char** argv) {
  Arguments arguments("check-budgets",
                      "Checks a run's report.json against a budget profile (config/budgets/<target>.yaml): every\n"
                      "task's p99 run time within its budget, no never-skip task missing a period. Prints one\n"
                      "line per task; exit code 1 when a budget is broken.");
  arguments.positional("REPORT", "report.json of a run");
  arguments.option("profile", "FILE", "budget profile (a config file with the budgets section)");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  if (!arguments.has("profile")) {
    std::fprintf(stderr, "%s: --profile is required (see --help)\n", kName);
    return 2;
  }
  const core::SystemConfigLoad profile = core::load_system_config(arguments.get("profile"));
  if (!profile.ok()) {
    std::fprintf(stderr, "%s: profile problem(s):\n%s", kName, profile.error_text().c_str());
    return 2;
  }
  std::map<std::string, TaskTiming> timing;
  std::string error;
  if (!read_timing(arguments.get("REPORT"), timing, error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 2;
  }
  int broken = 0;
  std::printf("%-20s %10s %10s %10s %10s %8s  %s\n", "task", "runs", "budget_us", "p99_us", "max_us", "overruns", "verdict");
  for (std::size_t i = 0; i < core::BudgetsConfig::kTaskCount; ++i) {
    const std::string task = core::BudgetsConfig::kTaskNames[i];
    const std::int64_t budget = profile.config.budgets.tasks[i].budget_us;
    const auto found = timing.find(task);
    if (found == timing.end() || found->second.p99_us < 0) {
      std::printf("%-20s %10s %10lld %10s %10s %8s  missing from the report\n", task.c_str(), "-",
                  static_cast<long long>(budget), "-", "-", "-");
      ++broken;
      continue;
    }
    const TaskTiming& t = found->second;
    const bool within = t.p99_us <= budget;
    const bool missed = never_skipped(task) && t.missed_periods > 0;
    const char* verdict = !within ? "OVER BUDGET (p99)" : missed ? "MISSED PERIODS" : "ok";
    broken += (!within || missed) ? 1 : 0;
    std::printf("%-20s %10lld %10lld %10lld %10lld %8lld  %s\n", task.c_str(), t.runs, static_cast<long long>(budget),
                t.p99_us, t.max_us, t.overruns, verdict);
  }
  std::printf("%s\n", broken == 0 ? "within budget" : "budget broken");
  return broken == 0 ? 0 : 1;
}

}  // namespace stereoscout::cli
