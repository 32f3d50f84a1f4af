// stereoscout config: validate a config file and show what a run would use.
#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "stereoscout/core/system_config.hpp"

namespace stereoscout::cli {

int run_config(int argc, char** argv) {
  Arguments arguments("config",
                      "Checks a config file against the schema (types, ranges, unknown keys) and\n"
                      "reports every problem with the file and the key. Keys left out keep the\n"
                      "paper's defaults.");
  arguments.option("config", "FILE", "config file to check", default_config_path());
  arguments.flag("print", "print the effective configuration (file over defaults) as YAML");
  arguments.flag("reference", "print the markdown reference of every key (docs/config.md)");
  if (!arguments.parse(argc, argv)) {
    return arguments.exit_code();
  }
  if (arguments.has("reference")) {
    std::fputs(core::config_reference_markdown().c_str(), stdout);
    return 0;
  }
  const std::string path = arguments.get("config");
  const core::SystemConfigLoad load = core::load_system_config(path);
  if (!load.ok()) {
    std::fprintf(stderr, "stereoscout config: %zu problem(s):\n%s", load.errors.size(), load.error_text().c_str());
    return 1;
  }
  if (arguments.has("print")) {
    std::fputs(core::to_yaml(load.config).c_str(), stdout);
    return 0;
  }
  std::printf("config OK: %s\n", path.c_str());
  return 0;
}

}  // namespace stereoscout::cli
