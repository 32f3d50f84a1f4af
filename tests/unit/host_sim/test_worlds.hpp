#pragma once
// Small worlds written by the tests themselves, and the path of the shipped ones.
#include <string>

#include <gtest/gtest.h>

#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/test/paths.hpp"

namespace stereoscout::host_sim::testing {

using stereoscout::test::source_path;

// A 10 m x 6 m room; `wall_texture` on all four walls, floor and ceiling as given.
inline std::string room_yaml(const std::string& wall_texture, const std::string& floor_texture = "tile",
                             const std::string& ceiling_texture = "low") {
  return "name: room\nseed: 3\nceiling_height: 2.5\nstart: [2, 3, 0]\n"
         "floor: {type: tile, texture: " + floor_texture + ", brightness: 0.5, contrast: 0.5}\n"
         "ceiling: {texture: " + ceiling_texture + ", brightness: 0.8, contrast: 0.2}\n"
         "walls:\n  - {points: [[0, 0], [10, 0], [10, 6], [0, 6], [0, 0]], texture: " + wall_texture +
         ", brightness: 0.5, contrast: 0.8}\n";
}

inline World load_or_fail(const std::string& yaml, const std::string& name = "test.yaml") {
  WorldLoad load = load_world_text(yaml, name);
  EXPECT_TRUE(load.ok()) << load.error_text();
  return load.world;
}

}  // namespace stereoscout::host_sim::testing
