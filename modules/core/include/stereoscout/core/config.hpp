#pragma once
// Typed configuration. Each config section is a plain struct whose member initialisers are
// the paper's defaults, plus a describe() function that walks its keys through a
// ConfigVisitor. The same describe() drives
//   - ConfigReader: loads YAML through cv::FileStorage, checks types and ranges, rejects
//     unknown and repeated keys; every error names the file, the key path and the problem;
//   - ConfigWriter: writes the effective configuration back as YAML (for logs and reports);
//   - the markdown reference in docs/config.md (a test keeps it in step with the code).
// Config is read at start-up only; none of this runs in the tick loop.

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace stereoscout::core {

struct NumberSpec {
  double min;
  double max;
  const char* unit;  // "" when dimensionless
  const char* help;
};

class ConfigVisitor {
 public:
  virtual ~ConfigVisitor() = default;
  virtual void begin_section(const char* key, const char* help) = 0;
  virtual void end_section() = 0;
  virtual void number(const char* key, double& value, const NumberSpec& spec) = 0;
  virtual void integer(const char* key, std::int64_t& value, const NumberSpec& spec) = 0;
  virtual void boolean(const char* key, bool& value, const char* help) = 0;
  virtual void text(const char* key, std::string& value, const char* help) = 0;
  // A text value restricted to `choices` (a nullptr-terminated list).
  virtual void choice(const char* key, std::string& value, const char* const* choices, const char* help) = 0;
  // A relation between keys that ranges alone cannot state; only the reader acts on it.
  virtual void require(bool holds, const char* key, const char* message) = 0;

  // Integer fields of any width go through the 64-bit hook with their own range.
  template <class Int, std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>, int> = 0>
  void integer_field(const char* key, Int& value, const NumberSpec& spec) {
    auto wide = static_cast<std::int64_t>(value);
    integer(key, wide, spec);
    value = static_cast<Int>(wide);
  }
};

// A config error: where and what.
struct ConfigError {
  std::string file;
  std::string key;  // dotted path, e.g. "filter.particles"; empty for file-level errors
  std::string message;
  std::string to_string() const;
};

// Reads one YAML document. Use: ConfigReader reader; if (!reader.open_file(path)) ...;
// describe(reader, config); reader.finish(); then reader.errors().
class ConfigReader final : public ConfigVisitor {
 public:
  ConfigReader();
  ~ConfigReader() override;
  ConfigReader(const ConfigReader&) = delete;
  ConfigReader& operator=(const ConfigReader&) = delete;

  bool open_file(const std::string& path);
  // `name` stands for the file name in messages.
  bool open_text(const std::string& yaml, const std::string& name);
  // Reports every key in the document that no describe() asked for.
  void finish();

  bool ok() const { return errors_.empty(); }
  const std::vector<ConfigError>& errors() const { return errors_; }
  std::string error_text() const;  // one error per line

  void begin_section(const char* key, const char* help) override;
  void end_section() override;
  void number(const char* key, double& value, const NumberSpec& spec) override;
  void integer(const char* key, std::int64_t& value, const NumberSpec& spec) override;
  void boolean(const char* key, bool& value, const char* help) override;
  void text(const char* key, std::string& value, const char* help) override;
  void choice(const char* key, std::string& value, const char* const* choices, const char* help) override;
  void require(bool holds, const char* key, const char* message) override;

 private:
  struct Impl;
  void add_error(const std::string& key_path, const std::string& message);
  std::unique_ptr<Impl> impl_;
  std::string file_;
  std::vector<ConfigError> errors_;
};

// Writes the values it visits as YAML text readable by ConfigReader.
class ConfigWriter final : public ConfigVisitor {
 public:
  const std::string& yaml() const { return text_; }

  void begin_section(const char* key, const char* help) override;
  void end_section() override;
  void number(const char* key, double& value, const NumberSpec& spec) override;
  void integer(const char* key, std::int64_t& value, const NumberSpec& spec) override;
  void boolean(const char* key, bool& value, const char* help) override;
  void text(const char* key, std::string& value, const char* help) override;
  void choice(const char* key, std::string& value, const char* const* choices, const char* help) override;
  void require(bool, const char*, const char*) override {}

 private:
  void line(const char* key, const std::string& value, const char* comment);
  std::string text_ = "%YAML:1.0\n";
  int depth_ = 0;
};

// Writes a markdown reference: one table per section with key, default, range, unit, help.
class ConfigMarkdownWriter final : public ConfigVisitor {
 public:
  const std::string& markdown() const { return text_; }

  void begin_section(const char* key, const char* help) override;
  void end_section() override;
  void number(const char* key, double& value, const NumberSpec& spec) override;
  void integer(const char* key, std::int64_t& value, const NumberSpec& spec) override;
  void boolean(const char* key, bool& value, const char* help) override;
  void text(const char* key, std::string& value, const char* help) override;
  void choice(const char* key, std::string& value, const char* const* choices, const char* help) override;
  void require(bool, const char*, const char*) override {}

 private:
  void row(const char* key, const std::string& value, const std::string& range, const char* unit,
           const char* help);
  std::vector<std::string> path_;
  std::string text_;
};

// Shortest text that reads back as exactly `value`.
std::string format_number(double value);

}  // namespace stereoscout::core
