#pragma once
// Where tests find the source tree (config, docs, worlds) and the real evaluation data.
// Both are compiled in by stereoscout_add_test; STEREOSCOUT_DATA_DIR in the environment
// overrides the data folder (default ../shared/data beside the clone).

#include <cstdlib>
#include <string>
#include <sys/stat.h>

namespace stereoscout::test {

inline std::string source_path(const std::string& relative) {
  return std::string(STEREOSCOUT_TEST_SOURCE_DIR) + "/" + relative;
}

inline std::string data_dir() {
  const char* from_environment = std::getenv("STEREOSCOUT_DATA_DIR");
  return from_environment != nullptr && *from_environment != '\0' ? from_environment
                                                                   : STEREOSCOUT_TEST_DATA_DIR;
}

// A path inside the data folder, or "" when it is not there (the caller then GTEST_SKIPs,
// naming what is missing).
inline std::string data_path(const std::string& relative) {
  const std::string path = data_dir() + "/" + relative;
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 ? path : std::string();
}

}  // namespace stereoscout::test
