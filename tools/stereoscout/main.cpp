// stereoscout: the onboard software of a stereo-vision exploring robot. One executable,
// one subcommand per job; see `stereoscout --help`.
#include <cstdio>
#include <cstring>

#include "commands.hpp"

namespace {

void print_help() {
  std::puts("usage: stereoscout <command> [options]   (stereoscout <command> --help for details)\n");
  std::puts("commands:");
  for (const stereoscout::cli::Command* command = stereoscout::cli::command_table(); command->name != nullptr;
       ++command) {
    std::printf("  %-16s %s\n", command->name, command->summary);
  }
  std::puts("\n  --version        print the version");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    print_help();
    return argc < 2 ? 2 : 0;
  }
  if (std::strcmp(argv[1], "--version") == 0) {
    std::printf("stereoscout %s\n", STEREOSCOUT_VERSION);
    return 0;
  }
  for (const stereoscout::cli::Command* command = stereoscout::cli::command_table(); command->name != nullptr;
       ++command) {
    if (std::strcmp(argv[1], command->name) == 0) {
      return command->run(argc - 2, argv + 2);
    }
  }
  std::fprintf(stderr, "stereoscout: unknown command '%s' (see stereoscout --help)\n", argv[1]);
  return 2;
}
