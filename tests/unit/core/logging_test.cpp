#include <gtest/gtest.h>

#include <string>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/logging.hpp"

namespace stereoscout::core {
namespace {

class FixedTime final : public TimeSource {
 public:
  std::int64_t now_ns() const override { return 1'500'000'000; }
};

TEST(Logger, FiltersByThresholdAndCountsPerLevel) {
  MemorySink sink;
  Logger logger(sink, LogLevel::info);
  logger.debug("hidden %d", 1);
  logger.info("particles %d", 1000);
  logger.warn("pool %s at %.1f%%", "landmarks", 99.5);
  ASSERT_EQ(sink.size(), 2u);
  EXPECT_STREQ(sink.line(0), "particles 1000");
  EXPECT_STREQ(sink.line(1), "pool landmarks at 99.5%");
  EXPECT_EQ(sink.level(1), LogLevel::warn);
  EXPECT_EQ(logger.count(LogLevel::debug), 0u);
  EXPECT_EQ(logger.count(LogLevel::info), 1u);
  EXPECT_EQ(logger.count(LogLevel::warn), 1u);
  logger.set_threshold(LogLevel::off);
  logger.error("nothing");
  EXPECT_EQ(sink.size(), 2u);
}

TEST(Logger, LongMessagesAreCutAndCounted) {
  MemorySink sink;
  Logger logger(sink, LogLevel::debug);
  const std::string long_text(1000, 'x');
  logger.info("%s", long_text.c_str());
  EXPECT_EQ(logger.truncated(), 1u);
  EXPECT_EQ(std::string(sink.line(0)).size(), MemorySink::kLineLength - 1);
}

TEST(Logger, MemorySinkKeepsTheNewestLines) {
  MemorySink sink;
  Logger logger(sink, LogLevel::debug);
  for (int i = 0; i < 100; ++i) {
    logger.info("line %d", i);
  }
  ASSERT_EQ(sink.size(), MemorySink::kLines);
  EXPECT_STREQ(sink.line(0), "line 36");
  EXPECT_STREQ(sink.line(MemorySink::kLines - 1), "line 99");
}

TEST(Logger, DoesNotAllocate) {
  MemorySink sink;
  FixedTime time;
  Logger logger(sink, LogLevel::debug, &time);
  logger.info("warm up %d", 0);
  AllocationScope scope;
  for (int i = 0; i < 100; ++i) {
    logger.info("update %d: %zu landmarks, ess %.3f, %s", i, static_cast<std::size_t>(i * 7), 0.5, "ok");
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

TEST(StreamSink, WritesTimestampLevelAndMessage) {
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  StreamSink sink(file);
  FixedTime time;
  Logger logger(sink, LogLevel::info, &time);
  logger.warn("grid cache %d/%d", 23, 64);
  std::rewind(file);
  char buffer[128] = {};
  ASSERT_NE(std::fgets(buffer, sizeof buffer, file), nullptr);
  std::fclose(file);
  EXPECT_STREQ(buffer, "[     1.500] warn  grid cache 23/64\n");
}

}  // namespace
}  // namespace stereoscout::core
