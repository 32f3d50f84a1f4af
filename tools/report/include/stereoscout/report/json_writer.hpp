#pragma once
// A small JSON writer for reports: keys in the order written, two-space indentation,
// numbers in their shortest exact form (core::format_number), non-finite numbers as null,
// strings escaped. The same values always give the same bytes, so report hashes compare.

#include <cstdint>
#include <string>
#include <vector>

namespace stereoscout::report {

class JsonWriter {
 public:
  JsonWriter& begin_object(const char* key = nullptr);
  JsonWriter& end_object();
  JsonWriter& begin_array(const char* key = nullptr);
  JsonWriter& end_array();
  JsonWriter& number(const char* key, double value);
  JsonWriter& integer(const char* key, std::int64_t value);
  JsonWriter& unsigned_integer(const char* key, std::uint64_t value);
  JsonWriter& boolean(const char* key, bool value);
  JsonWriter& text(const char* key, const std::string& value);
  JsonWriter& null(const char* key);
  // Array elements: pass key = nullptr.

  // The document, ending in a newline. The writer must be back at the top level.
  std::string str() const;

 private:
  void open_value(const char* key);
  void write_raw(const char* key, const std::string& value);
  std::string text_;
  std::vector<bool> first_in_scope_{true};
};

std::string json_escape(const std::string& text);

}  // namespace stereoscout::report
