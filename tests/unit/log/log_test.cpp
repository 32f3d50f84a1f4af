#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/log/reader.hpp"
#include "stereoscout/log/writer.hpp"

namespace stereoscout::log {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string temp_path(const std::string& name) { return ::testing::TempDir() + "stereoscout_" + name; }

Bytes read_bytes(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream stream(path, std::ios::binary);
  stream.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

core::OdometryReading odometry(std::uint64_t i) {
  core::OdometryReading reading;
  reading.timestamp_ns = static_cast<std::int64_t>(i) * 185'000'000;
  reading.sequence = i;
  reading.pose = {0.01 * static_cast<double>(i), -0.002 * static_cast<double>(i), 0.001 * static_cast<double>(i)};
  return reading;
}

// A log of `count` odometry records (and the end_of_run the writer adds).
std::string write_odometry_log(const std::string& name, std::uint64_t count) {
  const std::string path = temp_path(name);
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.open(path, error)) << error;
  const LogWriterOptions defaults;
  for (std::uint64_t i = 0; i < count; ++i) {
    // Drain before the queue can fill: a refused record counts as dropped, and the drop
    // count (which depends on thread timing) is written into end_of_run.
    if (i % defaults.queue_slots == defaults.queue_slots - 1) {
      writer.flush();
    }
    EXPECT_TRUE(writer.write_odometry(odometry(i)));
  }
  writer.close();
  EXPECT_EQ(writer.stats().records_dropped, 0u);
  return path;
}

// Reads every record, returning the odometry sequence numbers seen.
std::vector<std::uint64_t> read_odometry_sequences(const std::string& path, LogReaderStats* stats = nullptr) {
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.open(path, error)) << error;
  std::vector<std::uint64_t> sequences;
  LogRecord record;
  while (reader.next(record)) {
    if (record.type == RecordType::odometry) {
      core::OdometryReading reading;
      EXPECT_TRUE(decode_odometry(record.payload, record.size, record.timestamp_ns, reading));
      EXPECT_EQ(reading.pose.x, odometry(reading.sequence).pose.x);
      sequences.push_back(reading.sequence);
    }
  }
  if (stats != nullptr) {
    *stats = reader.stats();
  }
  return sequences;
}

std::size_t odometry_record_size() { return kRecordHeaderSize + kOdometryPayloadBytes + kRecordTrailerSize; }

TEST(LogFormat, Crc32MatchesTheStandardCheckValue) {
  const std::string text = "123456789";
  EXPECT_EQ(crc32(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), 0xCBF43926U);
}

TEST(LogFormat, LittleEndianRoundTrip) {
  std::uint8_t bytes[8];
  put_u32(bytes, 0x11223344U);
  EXPECT_EQ(bytes[0], 0x44);
  EXPECT_EQ(get_u32(bytes), 0x11223344U);
  put_f64(bytes, -0.125);
  EXPECT_EQ(get_f64(bytes), -0.125);
}

TEST(LogRoundTrip, EveryRecordTypeComesBackUnchanged) {
  const std::string path = temp_path("roundtrip.log");
  core::StereoFrame frame;
  frame.allocate(32, 24);
  for (int row = 0; row < 24; ++row) {
    for (int column = 0; column < 32; ++column) {
      frame.left.at<std::uint8_t>(row, column) = static_cast<std::uint8_t>(row * 7 + column);
      frame.right.at<std::uint8_t>(row, column) = static_cast<std::uint8_t>(row + column * 3);
    }
  }
  frame.timestamp_ns = 123;
  frame.sequence = 9;
  frame.pan_rad = 0.5;
  {
    LogWriter writer;
    std::string error;
    ASSERT_TRUE(writer.open(path, error)) << error;
    EXPECT_TRUE(writer.write_run_info(0, {42, 1, "stereoscout test"}));
    EXPECT_TRUE(writer.write_config(0, "filter:\n  particles: 7\n"));
    EXPECT_TRUE(writer.write_stereo_frame(frame));
    EXPECT_TRUE(writer.write_odometry(odometry(3)));
    EXPECT_TRUE(writer.write_gpio_event(200, {GpioEvent::emergency_stop, true}));
    EXPECT_TRUE(writer.write_drive_command(300, {0.12, -0.1}));
    EXPECT_TRUE(writer.write_ground_truth(350, core::Pose2{1.5, -2.0, 0.25}));
    writer.close(400);
    EXPECT_EQ(writer.stats().records_written, 8u);
    EXPECT_EQ(writer.stats().records_dropped, 0u);
  }
  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.open(path, error)) << error;
  LogRecord record;
  std::vector<RecordType> types;
  while (reader.next(record)) {
    types.push_back(record.type);
    switch (record.type) {
      case RecordType::run_info: {
        RunInfo info;
        ASSERT_TRUE(decode_run_info(record.payload, record.size, info));
        EXPECT_EQ(info.seed, 42u);
        EXPECT_EQ(info.program_version, "stereoscout test");
        break;
      }
      case RecordType::config:
        EXPECT_EQ(std::string(reinterpret_cast<const char*>(record.payload), record.size), "filter:\n  particles: 7\n");
        break;
      case RecordType::stereo_frame: {
        core::StereoFrame back;
        back.allocate(32, 24);
        ASSERT_TRUE(decode_stereo_frame(record.payload, record.size, record.timestamp_ns, back));
        EXPECT_EQ(cv::norm(back.left, frame.left, cv::NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(back.right, frame.right, cv::NORM_INF), 0.0);
        EXPECT_EQ(back.sequence, 9u);
        EXPECT_EQ(back.pan_rad, 0.5);
        EXPECT_EQ(back.timestamp_ns, 123);
        core::StereoFrame wrong_size;
        wrong_size.allocate(16, 24);
        EXPECT_FALSE(decode_stereo_frame(record.payload, record.size, 0, wrong_size));
        break;
      }
      case RecordType::gpio_event: {
        GpioEvent event;
        ASSERT_TRUE(decode_gpio_event(record.payload, record.size, event));
        EXPECT_EQ(event.line, GpioEvent::emergency_stop);
        EXPECT_TRUE(event.value);
        break;
      }
      case RecordType::drive_command: {
        core::DriveCommand command;
        ASSERT_TRUE(decode_drive_command(record.payload, record.size, command));
        EXPECT_EQ(command.linear_mps, 0.12);
        break;
      }
      case RecordType::end_of_run: {
        EndOfRun end;
        ASSERT_TRUE(decode_end_of_run(record.payload, record.size, end));
        EXPECT_EQ(end.records_written, 7u);
        EXPECT_EQ(end.records_dropped, 0u);
        EXPECT_EQ(record.timestamp_ns, 400);
        break;
      }
      case RecordType::ground_truth: {
        core::Pose2 pose;
        ASSERT_TRUE(decode_ground_truth(record.payload, record.size, pose));
        EXPECT_EQ(pose.x, 1.5);
        EXPECT_EQ(pose.y, -2.0);
        EXPECT_EQ(pose.theta, 0.25);
        EXPECT_EQ(record.timestamp_ns, 350);
        break;
      }
      case RecordType::odometry:
        break;
    }
  }
  EXPECT_EQ(types, (std::vector<RecordType>{RecordType::run_info, RecordType::config, RecordType::stereo_frame,
                                            RecordType::odometry, RecordType::gpio_event, RecordType::drive_command,
                                            RecordType::ground_truth, RecordType::end_of_run}));
  EXPECT_EQ(reader.stats().damaged, 0u);
  EXPECT_EQ(reader.stats().truncated_bytes, 0u);
}

TEST(LogRoundTrip, SameRecordsGiveByteIdenticalFiles) {
  EXPECT_EQ(read_bytes(write_odometry_log("same_a.log", 50)), read_bytes(write_odometry_log("same_b.log", 50)));
}

TEST(LogDamage, FlippedPayloadByteSkipsOnlyThatRecord) {
  const std::string path = write_odometry_log("flipped.log", 20);
  Bytes bytes = read_bytes(path);
  const std::size_t record_7 = kFileHeaderSize + 7 * odometry_record_size();
  bytes[record_7 + kRecordHeaderSize + 10] ^= 0x40;
  write_bytes(path, bytes);
  LogReaderStats stats;
  const std::vector<std::uint64_t> sequences = read_odometry_sequences(path, &stats);
  ASSERT_EQ(sequences.size(), 19u);
  EXPECT_EQ(sequences[6], 6u);
  EXPECT_EQ(sequences[7], 8u);  // 7 is gone, 8 follows
  EXPECT_EQ(stats.damaged, 1u);
  EXPECT_EQ(stats.bytes_skipped, odometry_record_size());
}

TEST(LogDamage, DamagedLengthFieldIsResynchronised) {
  const std::string path = write_odometry_log("length.log", 10);
  Bytes bytes = read_bytes(path);
  put_u32(bytes.data() + kFileHeaderSize + 2 * odometry_record_size() + 8, 0x7FFFFFFFU);
  write_bytes(path, bytes);
  LogReaderStats stats;
  EXPECT_EQ(read_odometry_sequences(path, &stats).size(), 9u);
  EXPECT_EQ(stats.damaged, 1u);
}

TEST(LogDamage, TruncatedFileReadsUpToItsLastWholeRecord) {
  const std::string path = write_odometry_log("truncated.log", 30);
  Bytes bytes = read_bytes(path);
  const std::size_t cut = kFileHeaderSize + 12 * odometry_record_size() + 17;  // inside record 12
  bytes.resize(cut);
  write_bytes(path, bytes);
  LogReaderStats stats;
  const std::vector<std::uint64_t> sequences = read_odometry_sequences(path, &stats);
  ASSERT_EQ(sequences.size(), 12u);
  EXPECT_EQ(sequences.back(), 11u);
  EXPECT_EQ(stats.truncated_bytes, 17u);
  EXPECT_EQ(stats.damaged, 0u);
}

TEST(LogDamage, RandomCorruptionNeverYieldsABadRecord) {
  const std::string clean_path = write_odometry_log("fuzz_clean.log", 40);
  const Bytes clean = read_bytes(clean_path);
  const std::string path = temp_path("fuzz.log");
  core::RandomStream random(2024, {core::stream_purpose::test, 0, 0});
  for (int trial = 0; trial < 200; ++trial) {
    Bytes bytes = clean;
    const std::uint32_t flips = 1 + random.uniform_index(8);
    for (std::uint32_t i = 0; i < flips; ++i) {
      const std::size_t at = kFileHeaderSize + random.uniform_index(static_cast<std::uint32_t>(bytes.size() - kFileHeaderSize));
      bytes[at] = static_cast<std::uint8_t>(random.next_u32());
    }
    if (random.uniform() < 0.3) {
      bytes.resize(kFileHeaderSize + random.uniform_index(static_cast<std::uint32_t>(bytes.size() - kFileHeaderSize)));
    }
    write_bytes(path, bytes);
    const std::vector<std::uint64_t> sequences = read_odometry_sequences(path);  // decodes and checks each
    ASSERT_LE(sequences.size(), 40u);
    for (std::size_t i = 1; i < sequences.size(); ++i) {
      ASSERT_LT(sequences[i - 1], sequences[i]) << "records out of order in trial " << trial;
    }
  }
}

TEST(LogOpen, BadFilesAreNamedWithTheProblem) {
  LogReader reader;
  std::string error;
  EXPECT_FALSE(reader.open(temp_path("does_not_exist.log"), error));
  EXPECT_NE(error.find("cannot open the log"), std::string::npos);

  const std::string not_a_log = temp_path("not_a_log.log");
  write_bytes(not_a_log, Bytes(100, 'x'));
  LogReader second;
  EXPECT_FALSE(second.open(not_a_log, error));
  EXPECT_EQ(error, not_a_log + ": not a stereoscout log (wrong magic bytes)");

  Bytes future = read_bytes(write_odometry_log("future.log", 1));
  put_u16(future.data() + 8, 99);
  const std::string future_path = temp_path("future.log");
  write_bytes(future_path, future);
  LogReader third;
  EXPECT_FALSE(third.open(future_path, error));
  EXPECT_NE(error.find("version 99 is not supported"), std::string::npos);
}

TEST(LogWriterQueue, OversizedRecordIsDroppedAndCounted) {
  LogWriterOptions options;
  options.max_payload_bytes = 64;
  LogWriter writer(options);
  std::string error;
  ASSERT_TRUE(writer.open(temp_path("small.log"), error)) << error;
  core::StereoFrame frame;
  frame.allocate(32, 24);
  EXPECT_FALSE(writer.write_stereo_frame(frame));
  EXPECT_TRUE(writer.write_odometry(odometry(1)));
  writer.close();
  EXPECT_EQ(writer.stats().records_dropped, 1u);
  EXPECT_EQ(writer.stats().records_written, 2u);  // odometry + end_of_run
}

TEST(LogWriterQueue, WritingDoesNotAllocate) {
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.open(temp_path("alloc.log"), error)) << error;
  writer.write_odometry(odometry(0));
  writer.flush();
  core::AllocationScope scope;
  for (std::uint64_t i = 1; i < 200; ++i) {
    if (!writer.write_odometry(odometry(i))) {
      writer.flush();
    }
  }
  writer.flush();
  EXPECT_EQ(scope.allocations(), 0u);
  writer.close();
}

}  // namespace
}  // namespace stereoscout::log
