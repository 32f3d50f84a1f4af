#pragma once
// A small world for the integration tests of the closed loop (explore-gt, the whole stack):
// 7 m x 5 m, two rooms joined by a 1.2 m door, a low box (below a planar laser) and a table.

namespace stereoscout::test {

inline constexpr const char* kTwoRoomsWorld = R"(
name: two_rooms
seed: 5
ceiling_height: 2.6
start: [1.2, 1.2, 20]
floor: {type: tile, texture: tile, brightness: 0.5, contrast: 0.5}
ceiling: {texture: low, brightness: 0.8, contrast: 0.2}
walls:
  - {points: [[0, 0], [7, 0], [7, 5], [0, 5], [0, 0]], texture: brick, brightness: 0.5, contrast: 0.7}
  - {points: [[4, 0], [4, 1.6]], texture: wood, brightness: 0.5, contrast: 0.7}
  - {points: [[4, 2.8], [4, 5]], texture: wood, brightness: 0.5, contrast: 0.7}
boxes:
  - {center: [2.2, 3.6], size: [0.8, 0.6], z: [0, 0.15], texture: wood, brightness: 0.5, contrast: 0.7}
  - {center: [5.8, 3.8], size: [1.2, 0.8], z: [0.7, 0.75], texture: wood, brightness: 0.5, contrast: 0.7}
)";

}  // namespace stereoscout::test
