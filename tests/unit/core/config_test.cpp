#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "stereoscout/core/system_config.hpp"
#include "stereoscout/test/paths.hpp"

namespace stereoscout::core {
namespace {

using test::source_path;

std::string read_file(const std::string& path) {
  std::ifstream stream(path);
  std::ostringstream contents;
  contents << stream.rdbuf();
  return contents.str();
}

TEST(Config, DefaultsAreThePapersNumbers) {
  const SystemConfig config;
  EXPECT_EQ(config.filter.particles, 1000);
  EXPECT_DOUBLE_EQ(config.robot.max_speed_mps, 0.12);
  EXPECT_DOUBLE_EQ(config.robot.max_turn_rate_deg_s, 8.0);
  EXPECT_DOUBLE_EQ(config.robot.update_min_translation_m, 0.07);
  EXPECT_DOUBLE_EQ(config.robot.update_min_rotation_deg, 1.0);
  EXPECT_DOUBLE_EQ(config.vision.sigma_u_px, 10.0);
  EXPECT_DOUBLE_EQ(config.vision.sigma_d_px, 0.5);
  EXPECT_EQ(config.grid.width_cells, 700);
  EXPECT_DOUBLE_EQ(config.grid.resolution_m, 0.10);
  EXPECT_DOUBLE_EQ(config.explore.preferred_distance_m, 2.0);
  EXPECT_DOUBLE_EQ(config.explore.distance_sigma_m, 0.5);
  EXPECT_DOUBLE_EQ(config.explore.ray_step_deg, 5.0);
  EXPECT_DOUBLE_EQ(config.camera.baseline_m, 0.10);
}

TEST(Config, ShippedFileLoadsCleanly) {
  const SystemConfigLoad load = load_system_config(source_path("config/stereoscout.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_EQ(load.config.filter.particles, 1000);
}

// The 5 cm variants keep the default's metric sizes: the grid's extent, the lethal margin
// beyond the robot's radius and the goal candidates' lattice.
TEST(Config, TheFiveCentimetreGridVariantsKeepTheDefaultsMetricSizes) {
  for (const char* file : {"config/grid-5cm.yaml", "config/grid-5cm-near.yaml"}) {
    SCOPED_TRACE(file);
    const SystemConfigLoad load = load_system_config(source_path(file));
    ASSERT_TRUE(load.ok()) << load.error_text();
    const SystemConfig defaults;
    const SystemConfig& variant = load.config;
    EXPECT_DOUBLE_EQ(variant.grid.resolution_m, 0.05);
    EXPECT_DOUBLE_EQ(variant.grid.width_cells * variant.grid.resolution_m,
                     defaults.grid.width_cells * defaults.grid.resolution_m);
    EXPECT_DOUBLE_EQ(variant.grid.height_cells * variant.grid.resolution_m,
                     defaults.grid.height_cells * defaults.grid.resolution_m);
    EXPECT_DOUBLE_EQ(variant.explore.lethal_margin_cells * variant.grid.resolution_m,
                     defaults.explore.lethal_margin_cells * defaults.grid.resolution_m);
    EXPECT_DOUBLE_EQ(variant.explore.candidate_stride_cells * variant.grid.resolution_m,
                     defaults.explore.candidate_stride_cells * defaults.grid.resolution_m);
    EXPECT_EQ(variant.filter.particles, defaults.filter.particles);  // the rest is the default's
  }
}

// ... and the near variant adds what its runs measured with: far hits weighed by their range
// and the dense matcher's near range to 0.42 m.
TEST(Config, TheNearVariantWeighsFarHitsAndSearchesNinetySixDisparities) {
  const SystemConfigLoad load = load_system_config(source_path("config/grid-5cm-near.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_DOUBLE_EQ(load.config.grid.hit_full_weight_range_m, 3.0);
  EXPECT_EQ(load.config.vision.dense_num_disparities, 96);
  EXPECT_EQ(load.config.vision.max_features, SystemConfig{}.vision.max_features);
}

TEST(Config, ValuesOverrideDefaultsAndOmittedKeysKeepThem) {
  const SystemConfigLoad load = load_system_config_text(
      "filter:\n  particles: 2000\nrobot:\n  max_speed_mps: 0.2\ncamera:\n  has_pan_unit: false\n", "test.yaml");
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_EQ(load.config.filter.particles, 2000);
  EXPECT_DOUBLE_EQ(load.config.robot.max_speed_mps, 0.2);
  EXPECT_FALSE(load.config.camera.has_pan_unit);
  EXPECT_DOUBLE_EQ(load.config.robot.max_turn_rate_deg_s, 8.0);
}

TEST(Config, UnknownKeyIsRejectedWithFileKeyAndSuggestion) {
  const SystemConfigLoad load = load_system_config_text("filter:\n  partcles: 2000\n", "robot1.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].file, "robot1.yaml");
  EXPECT_EQ(load.errors[0].key, "filter.partcles");
  EXPECT_EQ(load.errors[0].to_string(), "robot1.yaml: filter.partcles: unknown key (did you mean 'particles'?)");
}

TEST(Config, UnknownSectionIsRejected) {
  const SystemConfigLoad load = load_system_config_text("lidar:\n  range_m: 30\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].key, "lidar");
  EXPECT_NE(load.errors[0].message.find("unknown key"), std::string::npos);
}

TEST(Config, WrongTypeIsRejected) {
  const SystemConfigLoad load = load_system_config_text("filter:\n  particles: many\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "c.yaml: filter.particles: expected an integer, got the text 'many'");
  EXPECT_EQ(load.config.filter.particles, 1000);  // the default stays
}

TEST(Config, RealWhereIntegerExpectedIsRejected) {
  const SystemConfigLoad load = load_system_config_text("grid:\n  width_cells: 700.5\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "c.yaml: grid.width_cells: expected an integer, got the number 700.5");
}

TEST(Config, OutOfRangeIsRejected) {
  const SystemConfigLoad load = load_system_config_text("robot:\n  max_speed_mps: -0.5\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "c.yaml: robot.max_speed_mps: -0.5 is out of range [0.01, 2]");
}

TEST(Config, EveryProblemIsReportedNotJustTheFirst) {
  const SystemConfigLoad load = load_system_config_text(
      "filter:\n  particles: many\n  bogus: 1\nrobot:\n  max_speed_mps: 9\n", "c.yaml");
  EXPECT_EQ(load.errors.size(), 3u) << load.error_text();
}

TEST(Config, CrossKeyRuleIsChecked) {
  const SystemConfigLoad load =
      load_system_config_text("filter:\n  particles: 3000\n  particle_capacity: 2000\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].key, "filter.particles");
  EXPECT_NE(load.errors[0].message.find("particle_capacity"), std::string::npos);
}

TEST(Config, BooleansChoicesAndSectionsAreTyped) {
  SystemConfigLoad load = load_system_config_text("camera:\n  has_pan_unit: maybe\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_NE(load.errors[0].message.find("expected true or false"), std::string::npos);

  load = load_system_config_text("run:\n  localization: gps\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "c.yaml: run.localization: 'gps' is not one of: rbpf, groundtruth, odometry");

  load = load_system_config_text("robot: 3\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "c.yaml: robot: expected a section of keys, got the integer 3");
}

TEST(Config, RepeatedKeyIsRejected) {
  const SystemConfigLoad load = load_system_config_text("filter:\n  particles: 10\n  particles: 20\n", "c.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].message, "key given more than once");
}

TEST(Config, MissingAndMalformedFilesNameTheFile) {
  SystemConfigLoad load = load_system_config("/nonexistent/stereoscout.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].to_string(), "/nonexistent/stereoscout.yaml: cannot open the file");

  load = load_system_config_text("filter:\n  particles: [1, 2\n", "broken.yaml");
  ASSERT_EQ(load.errors.size(), 1u);
  EXPECT_EQ(load.errors[0].file, "broken.yaml");
  EXPECT_NE(load.errors[0].message.find("not valid YAML"), std::string::npos);
}

TEST(Config, WrittenYamlLoadsBackToTheSameValues) {
  SystemConfig config;
  config.filter.particles = 1234;
  config.robot.radius_m = 0.123456789;
  config.run.localization = "groundtruth";
  config.budgets.tasks[3].budget_us = 42;
  const SystemConfigLoad load = load_system_config_text(to_yaml(config), "written.yaml");
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_EQ(to_yaml(load.config), to_yaml(config));
  EXPECT_EQ(load.config.filter.particles, 1234);
  EXPECT_EQ(load.config.robot.radius_m, 0.123456789);
}

// docs/config.md embeds the generated reference; this keeps the document true.
TEST(Config, DocumentationListsEveryKeyWithItsDefault) {
  const std::string doc = read_file(source_path("docs/config.md"));
  ASSERT_FALSE(doc.empty()) << "docs/config.md not found";
  EXPECT_NE(doc.find(config_reference_markdown()), std::string::npos)
      << "docs/config.md is out of date: regenerate its reference part with `stereoscout config --reference`";
}

TEST(FormatNumber, ShortestRoundTrip) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(700.0), "700");
  EXPECT_EQ(format_number(-0.4), "-0.4");
  EXPECT_EQ(format_number(0.123456789), "0.123456789");
  EXPECT_EQ(format_number(1e7), "10000000");
}

}  // namespace
}  // namespace stereoscout::core
