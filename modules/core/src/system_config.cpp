#include "stereoscout/core/system_config.hpp"

namespace stereoscout::core {
namespace {

SystemConfigLoad finish_load(ConfigReader& reader, bool opened) {
  SystemConfigLoad load;
  if (opened) {
    describe(reader, load.config);
    reader.finish();
  }
  load.errors = reader.errors();
  return load;
}

}  // namespace

void describe(ConfigVisitor& visitor, SystemConfig& config) {
  describe(visitor, config.run);
  describe(visitor, config.robot);
  describe(visitor, config.camera);
  describe(visitor, config.vision);
  describe(visitor, config.filter);
  describe(visitor, config.grid);
  describe(visitor, config.explore);
  describe(visitor, config.budgets);
  describe(visitor, config.sim);
  describe(visitor, config.robot_pc);
  describe(visitor, config.dataset);
}

std::string SystemConfigLoad::error_text() const {
  std::string text;
  for (const ConfigError& error : errors) {
    text += error.to_string() + "\n";
  }
  return text;
}

SystemConfigLoad load_system_config(const std::string& path) {
  ConfigReader reader;
  const bool opened = reader.open_file(path);
  return finish_load(reader, opened);
}

SystemConfigLoad load_system_config_text(const std::string& yaml, const std::string& name) {
  ConfigReader reader;
  const bool opened = reader.open_text(yaml, name);
  return finish_load(reader, opened);
}

std::string to_yaml(const SystemConfig& config) {
  SystemConfig copy = config;
  ConfigWriter writer;
  describe(writer, copy);
  return writer.yaml();
}

std::string config_reference_markdown() {
  SystemConfig defaults;
  ConfigMarkdownWriter writer;
  describe(writer, defaults);
  return writer.markdown();
}

}  // namespace stereoscout::core
