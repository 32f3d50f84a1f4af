#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>

#include "stereoscout/report/json_writer.hpp"
#include "stereoscout/report/sha256.hpp"

namespace stereoscout::report {
namespace {

std::string digest(const std::string& text) {
  Sha256 hash;
  hash.update(text);
  return hash.finish_hex();
}

// FIPS 180-4 examples and the standard long-message vector.
TEST(Sha256, KnownAnswers) {
  EXPECT_EQ(digest(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(digest("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(digest("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(digest(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PiecewiseUpdatesEqualOneUpdate) {
  const std::string text(200, 'x');
  Sha256 pieces;
  for (std::size_t i = 0; i < text.size(); i += 7) {
    pieces.update(text.substr(i, 7));
  }
  EXPECT_EQ(pieces.finish_hex(), digest(text));
}

TEST(Sha256, FileDigestAndMissingFile) {
  const std::string path = ::testing::TempDir() + "stereoscout_digest.txt";
  std::ofstream(path) << "abc";
  std::string hex;
  std::string error;
  ASSERT_TRUE(sha256_file(path, hex, error)) << error;
  EXPECT_EQ(hex, digest("abc"));
  EXPECT_FALSE(sha256_file("/nonexistent/file", hex, error));
  EXPECT_NE(error.find("/nonexistent/file: cannot read"), std::string::npos);
}

TEST(JsonWriter, NestedDocumentIsStableAndValid) {
  JsonWriter json;
  json.begin_object()
      .number("coverage", 0.957)
      .integer("collisions", 0)
      .text("world", "lab \"two rooms\"\n")
      .number("ate_rmse_m", std::numeric_limits<double>::quiet_NaN())
      .begin_object("timing")
      .begin_object("capture")
      .integer("median_us", 850)
      .end_object()
      .end_object()
      .begin_array("seeds")
      .integer(nullptr, 1)
      .integer(nullptr, 2)
      .end_array()
      .begin_object("empty")
      .end_object()
      .end_object();
  EXPECT_EQ(json.str(),
            "{\n"
            "  \"coverage\": 0.957,\n"
            "  \"collisions\": 0,\n"
            "  \"world\": \"lab \\\"two rooms\\\"\\n\",\n"
            "  \"ate_rmse_m\": null,\n"
            "  \"timing\": {\n"
            "    \"capture\": {\n"
            "      \"median_us\": 850\n"
            "    }\n"
            "  },\n"
            "  \"seeds\": [\n"
            "    1,\n"
            "    2\n"
            "  ],\n"
            "  \"empty\": {}\n"
            "}\n");
}

TEST(JsonWriter, EscapesControlCharacters) { EXPECT_EQ(json_escape(std::string("a\x01") + "b"), "\"a\\u0001b\""); }

}  // namespace
}  // namespace stereoscout::report
