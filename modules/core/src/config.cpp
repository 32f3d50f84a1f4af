#include "stereoscout/core/config.hpp"

#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace stereoscout::core {
namespace {

std::string join_key(const std::string& path, const char* key) {
  return path.empty() ? std::string(key) : path + "." + key;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    previous[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

// How a node looks to a user, for "expected X, got Y" messages.
std::string describe_node(const cv::FileNode& node) {
  if (node.isString()) {
    return "the text '" + static_cast<std::string>(node) + "'";
  }
  if (node.isInt()) {
    return "the integer " + std::to_string(static_cast<int>(node));
  }
  if (node.isReal()) {
    return "the number " + format_number(static_cast<double>(node));
  }
  if (node.isMap()) {
    return "a section";
  }
  if (node.isSeq()) {
    return "a list";
  }
  return "an empty value";
}

std::string range_text(const NumberSpec& spec) {
  return "[" + format_number(spec.min) + ", " + format_number(spec.max) + "]";
}

}  // namespace

std::string format_number(double value) {
  char buffer[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) {
      break;
    }
  }
  // Whole numbers read better without an exponent (700, not 7e+02).
  if (std::strchr(buffer, 'e') != nullptr && value == std::floor(value) && std::abs(value) < 1e15) {
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
  }
  return buffer;
}

std::string ConfigError::to_string() const {
  if (key.empty()) {
    return file + ": " + message;
  }
  return file + ": " + key + ": " + message;
}

struct ConfigReader::Impl {
  struct Frame {
    cv::FileNode node;  // empty when the section is absent from the file
    std::string path;
    std::vector<std::string> asked;
  };
  cv::FileStorage storage;
  std::vector<Frame> frames;

  Frame& top() { return frames.back(); }

  // The child `key` of the current section, or an empty node. Records that it was asked for.
  cv::FileNode child(const char* key) {
    Frame& frame = top();
    frame.asked.emplace_back(key);
    if (frame.node.empty() || !frame.node.isMap()) {
      return {};
    }
    return frame.node[key];
  }
};

ConfigReader::ConfigReader() : impl_(std::make_unique<Impl>()) {}
ConfigReader::~ConfigReader() = default;

void ConfigReader::add_error(const std::string& key_path, const std::string& message) {
  errors_.push_back({file_, key_path, message});
}

bool ConfigReader::open_file(const std::string& path) {
  file_ = path;
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    add_error("", "cannot open the file");
    return false;
  }
  std::ostringstream contents;
  contents << stream.rdbuf();
  return open_text(contents.str(), path);
}

bool ConfigReader::open_text(const std::string& yaml, const std::string& name) {
  file_ = name;
  // cv::FileStorage insists on a "%YAML:1.0" first line; users write plain YAML.
  const std::string document = yaml.rfind("%YAML", 0) == 0 ? yaml : "%YAML:1.0\n" + yaml;
  try {
    impl_->storage.open(document, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& error) {
    add_error("", "not valid YAML (" + error.err + (error.func.empty() ? "" : ": " + error.func) + ")");
    return false;
  }
  if (!impl_->storage.isOpened()) {
    add_error("", "not valid YAML");
    return false;
  }
  cv::FileNode root = impl_->storage.root();
  if (!root.isMap() && !root.empty() && !root.isNone()) {
    add_error("", "the top level must be a set of sections (key: value)");
    return false;
  }
  impl_->frames.clear();
  impl_->frames.push_back({root, "", {}});
  return true;
}

void ConfigReader::begin_section(const char* key, const char* /*help*/) {
  const std::string path = join_key(impl_->top().path, key);
  cv::FileNode node = impl_->child(key);
  if (!node.empty() && !node.isMap()) {
    add_error(path, "expected a section of keys, got " + describe_node(node));
    node = cv::FileNode();
  }
  impl_->frames.push_back({node, path, {}});
}

void ConfigReader::end_section() {
  Impl::Frame& frame = impl_->top();
  if (!frame.node.empty() && frame.node.isMap()) {
    std::vector<std::string> seen;
    for (const cv::FileNode& entry : frame.node) {
      const std::string name = entry.name();
      const std::string path = join_key(frame.path, name.c_str());
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
        add_error(path, "key given more than once");
        continue;
      }
      seen.push_back(name);
      if (std::find(frame.asked.begin(), frame.asked.end(), name) != frame.asked.end()) {
        continue;
      }
      std::string message = "unknown key";
      for (const std::string& known : frame.asked) {
        if (edit_distance(name, known) <= 2) {
          message += " (did you mean '" + known + "'?)";
          break;
        }
      }
      add_error(path, message);
    }
  }
  impl_->frames.pop_back();
}

void ConfigReader::finish() {
  while (!impl_->frames.empty()) {
    end_section();
  }
}

void ConfigReader::number(const char* key, double& value, const NumberSpec& spec) {
  const std::string path = join_key(impl_->top().path, key);
  const cv::FileNode node = impl_->child(key);
  if (node.empty()) {
    return;
  }
  if (!node.isInt() && !node.isReal()) {
    add_error(path, "expected a number, got " + describe_node(node));
    return;
  }
  const double read = node.isInt() ? static_cast<double>(static_cast<int>(node)) : static_cast<double>(node);
  if (!std::isfinite(read) || read < spec.min || read > spec.max) {
    add_error(path, format_number(read) + " is out of range " + range_text(spec));
    return;
  }
  value = read;
}

void ConfigReader::integer(const char* key, std::int64_t& value, const NumberSpec& spec) {
  const std::string path = join_key(impl_->top().path, key);
  const cv::FileNode node = impl_->child(key);
  if (node.empty()) {
    return;
  }
  if (!node.isInt()) {
    add_error(path, "expected an integer, got " + describe_node(node));
    return;
  }
  const auto read = static_cast<std::int64_t>(static_cast<int>(node));
  if (static_cast<double>(read) < spec.min || static_cast<double>(read) > spec.max) {
    add_error(path, std::to_string(read) + " is out of range " + range_text(spec));
    return;
  }
  value = read;
}

void ConfigReader::boolean(const char* key, bool& value, const char* /*help*/) {
  const std::string path = join_key(impl_->top().path, key);
  const cv::FileNode node = impl_->child(key);
  if (node.empty()) {
    return;
  }
  if (node.isString()) {
    const std::string word = node;
    if (word == "true") {
      value = true;
      return;
    }
    if (word == "false") {
      value = false;
      return;
    }
  }
  add_error(path, "expected true or false, got " + describe_node(node));
}

void ConfigReader::text(const char* key, std::string& value, const char* /*help*/) {
  const std::string path = join_key(impl_->top().path, key);
  const cv::FileNode node = impl_->child(key);
  if (node.empty()) {
    return;
  }
  if (!node.isString()) {
    add_error(path, "expected text, got " + describe_node(node));
    return;
  }
  value = static_cast<std::string>(node);
}

void ConfigReader::choice(const char* key, std::string& value, const char* const* choices, const char* help) {
  std::string read = value;
  const std::size_t errors_before = errors_.size();
  text(key, read, help);
  if (errors_.size() != errors_before) {
    return;
  }
  std::string allowed;
  for (const char* const* option = choices; *option != nullptr; ++option) {
    if (read == *option) {
      value = read;
      return;
    }
    allowed += allowed.empty() ? *option : std::string(", ") + *option;
  }
  add_error(join_key(impl_->top().path, key), "'" + read + "' is not one of: " + allowed);
}

void ConfigReader::require(bool holds, const char* key, const char* message) {
  if (!holds) {
    add_error(join_key(impl_->top().path, key), message);
  }
}

std::string ConfigReader::error_text() const {
  std::string text;
  for (const ConfigError& error : errors_) {
    text += error.to_string() + "\n";
  }
  return text;
}

// --- ConfigWriter ---------------------------------------------------------------------

void ConfigWriter::line(const char* key, const std::string& value, const char* comment) {
  text_.append(static_cast<std::size_t>(depth_) * 2, ' ');
  text_ += key;
  text_ += ":";
  if (!value.empty()) {
    text_ += " " + value;
  }
  if (comment != nullptr && *comment != '\0') {
    text_ += std::string("  # ") + comment;
  }
  text_ += "\n";
}

void ConfigWriter::begin_section(const char* key, const char* /*help*/) {
  line(key, "", nullptr);
  ++depth_;
}
void ConfigWriter::end_section() { --depth_; }
void ConfigWriter::number(const char* key, double& value, const NumberSpec& spec) {
  line(key, format_number(value), spec.unit);
}
void ConfigWriter::integer(const char* key, std::int64_t& value, const NumberSpec& spec) {
  line(key, std::to_string(value), spec.unit);
}
void ConfigWriter::boolean(const char* key, bool& value, const char*) { line(key, value ? "true" : "false", nullptr); }
void ConfigWriter::text(const char* key, std::string& value, const char*) { line(key, "\"" + value + "\"", nullptr); }
void ConfigWriter::choice(const char* key, std::string& value, const char* const*, const char*) {
  line(key, "\"" + value + "\"", nullptr);
}

// --- ConfigMarkdownWriter ---------------------------------------------------------------

void ConfigMarkdownWriter::begin_section(const char* key, const char* help) {
  path_.emplace_back(key);
  std::string dotted;
  for (const std::string& part : path_) {
    dotted += dotted.empty() ? part : "." + part;
  }
  text_ += "\n### `" + dotted + "`\n\n" + help + "\n\n";
  text_ += "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
}
void ConfigMarkdownWriter::end_section() { path_.pop_back(); }

void ConfigMarkdownWriter::row(const char* key, const std::string& value, const std::string& range,
                               const char* unit, const char* help) {
  text_ += "| `" + std::string(key) + "` | " + value + " | " + range + " | " + unit + " | " + help + " |\n";
}
void ConfigMarkdownWriter::number(const char* key, double& value, const NumberSpec& spec) {
  row(key, format_number(value), range_text(spec), spec.unit, spec.help);
}
void ConfigMarkdownWriter::integer(const char* key, std::int64_t& value, const NumberSpec& spec) {
  row(key, std::to_string(value), range_text(spec), spec.unit, spec.help);
}
void ConfigMarkdownWriter::boolean(const char* key, bool& value, const char* help) {
  row(key, value ? "true" : "false", "true, false", "", help);
}
void ConfigMarkdownWriter::text(const char* key, std::string& value, const char* help) {
  row(key, "`" + value + "`", "text", "", help);
}
void ConfigMarkdownWriter::choice(const char* key, std::string& value, const char* const* choices, const char* help) {
  std::string allowed;
  for (const char* const* option = choices; *option != nullptr; ++option) {
    allowed += allowed.empty() ? *option : std::string(", ") + *option;
  }
  row(key, "`" + value + "`", allowed, "", help);
}

}  // namespace stereoscout::core
