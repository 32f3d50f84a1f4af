#include "stereoscout/report/json_writer.hpp"

#include <cmath>
#include <cstdio>

#include "stereoscout/core/check.hpp"
#include "stereoscout/core/config.hpp"

namespace stereoscout::report {

std::string json_escape(const std::string& text) {
  std::string escaped = "\"";
  for (char c : text) {
    switch (c) {
      case '"': escaped += "\\\""; break;
      case '\\': escaped += "\\\\"; break;
      case '\n': escaped += "\\n"; break;
      case '\r': escaped += "\\r"; break;
      case '\t': escaped += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char code[8];
          std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          escaped += code;
        } else {
          escaped += c;
        }
    }
  }
  return escaped + "\"";
}

void JsonWriter::open_value(const char* key) {
  if (!first_in_scope_.back()) {
    text_ += ",";
  }
  first_in_scope_.back() = false;
  if (first_in_scope_.size() > 1) {
    text_ += "\n" + std::string(2 * (first_in_scope_.size() - 1), ' ');
  }
  if (key != nullptr) {
    text_ += json_escape(key) + ": ";
  }
}

void JsonWriter::write_raw(const char* key, const std::string& value) {
  open_value(key);
  text_ += value;
}

JsonWriter& JsonWriter::begin_object(const char* key) {
  open_value(key);
  text_ += "{";
  first_in_scope_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  STEREOSCOUT_CHECK(first_in_scope_.size() > 1, "JsonWriter::end_object without an open object");
  const bool empty = first_in_scope_.back();
  first_in_scope_.pop_back();
  text_ += empty ? "}" : "\n" + std::string(2 * (first_in_scope_.size() - 1), ' ') + "}";
  return *this;
}

JsonWriter& JsonWriter::begin_array(const char* key) {
  open_value(key);
  text_ += "[";
  first_in_scope_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  STEREOSCOUT_CHECK(first_in_scope_.size() > 1, "JsonWriter::end_array without an open array");
  const bool empty = first_in_scope_.back();
  first_in_scope_.pop_back();
  text_ += empty ? "]" : "\n" + std::string(2 * (first_in_scope_.size() - 1), ' ') + "]";
  return *this;
}

JsonWriter& JsonWriter::number(const char* key, double value) {
  write_raw(key, std::isfinite(value) ? core::format_number(value) : "null");
  return *this;
}

JsonWriter& JsonWriter::integer(const char* key, std::int64_t value) {
  write_raw(key, std::to_string(value));
  return *this;
}

JsonWriter& JsonWriter::unsigned_integer(const char* key, std::uint64_t value) {
  write_raw(key, std::to_string(value));
  return *this;
}

JsonWriter& JsonWriter::boolean(const char* key, bool value) {
  write_raw(key, value ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::text(const char* key, const std::string& value) {
  write_raw(key, json_escape(value));
  return *this;
}

JsonWriter& JsonWriter::null(const char* key) {
  write_raw(key, "null");
  return *this;
}

std::string JsonWriter::str() const {
  STEREOSCOUT_CHECK(first_in_scope_.size() == 1, "JsonWriter::str with an object or array still open");
  return text_ + "\n";
}

}  // namespace stereoscout::report
