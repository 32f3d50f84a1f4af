#pragma once
// The simulated 2.5D indoor world: everything is a vertical extrusion of a floor-plan shape
// over a z-range (docs/worlds.md). World files are YAML; load_world() checks every key and
// reports errors naming the file and the key.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::host_sim {

// Procedural textures, generated once per world from its seed (textures.hpp).
enum class Texture : std::uint8_t { blank, low, noise, brick, wood, poster, books, tile, carpet };
inline constexpr int kTextureCount = 9;
// Name in world files of each Texture, in enum order.
inline constexpr const char* kTextureNames[kTextureCount] = {"blank", "low",    "noise", "brick", "wood",
                                                             "poster", "books", "tile",  "carpet"};

// How a surface looks: gray level = 255 * exposure * light gain * (brightness + contrast *
// (texel - 0.5)), with texels in [0, 1]. Brightness above 1 saturates (windows).
struct Surface {
  Texture texture = Texture::blank;
  float brightness = 0.5F;
  float contrast = 0.5F;
  // Offset into the texture tile so that two surfaces with the same texture do not show
  // identical patches (set per surface from the world seed).
  float texture_offset_u_m = 0.0F;
  float texture_offset_v_m = 0.0F;
};

// A vertical face over the segment a-b (zero thickness, visible from both sides).
struct WallPiece {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  double z_min = 0.0;
  double z_max = 2.5;
  double texture_u0_m = 0.0;  // texture coordinate at `a` (distance along the original wall)
  Surface surface;
};

// A solid prism: a simple closed polygon footprint extruded over [z_min, z_max]. Boxes,
// table tops, shelves and bookcases are prisms.
struct Prism {
  std::vector<Eigen::Vector2d> polygon;  // without the repeated closing vertex
  double z_min = 0.0;
  double z_max = 1.0;
  Surface surface;
};

struct Cylinder {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.2;
  double z_min = 0.0;
  double z_max = 1.0;
  Surface surface;
};

// A person walking at constant speed along a closed loop of waypoints.
struct Person {
  std::vector<Eigen::Vector2d> waypoints;
  double speed_mps = 0.5;
  double radius = 0.25;
  double height = 1.7;
  Surface surface;
};

// A door: an opening of a wall that reaches down to the floor (an opening of kind door with
// bottom 0), between its two jambs. The walls beside it are WallPieces; this only names the
// gap, for the simulator's door visits (door_visits.hpp).
struct Doorway {
  Eigen::Vector2d jamb_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d jamb_b = Eigen::Vector2d::Zero();
};

enum class FloorType : std::uint8_t { tile = 0, carpet = 1 };

struct FloorRegion {
  std::vector<Eigen::Vector2d> polygon;
  FloorType type = FloorType::carpet;
  Surface surface;
};

// Natural light: surfaces and floor inside the polygon are `gain` times brighter.
struct LightRegion {
  std::vector<Eigen::Vector2d> polygon;
  double gain = 1.5;
};

struct World {
  std::string name;
  std::string file;
  std::uint64_t texture_seed = 1;
  // Tiles drawn per texture (textures.hpp): 1, one tile repeating every 2.56 m over every
  // surface of its texture; more, each 2.56 m cell of a surface shows one of them, picked by
  // a hash of the cell.
  int texture_variants = 1;
  double ceiling_height = 2.8;
  core::Pose2 start;
  FloorType floor_type = FloorType::tile;
  Surface floor;
  Surface ceiling;
  std::vector<WallPiece> walls;
  std::vector<Doorway> doorways;  // in the order of the walls and their openings
  std::vector<Prism> prisms;
  std::vector<Cylinder> cylinders;
  std::vector<Person> people;
  std::vector<FloorRegion> floor_regions;
  std::vector<LightRegion> lights;

  // Axis-aligned bounds of all static geometry in the floor plane.
  Eigen::Vector2d bounds_min() const;
  Eigen::Vector2d bounds_max() const;
  // Floor type and light gain at a floor point (the last region listed wins).
  FloorType floor_type_at(const Eigen::Vector2d& point) const;
  double light_gain_at(const Eigen::Vector2d& point) const;
  // Where person `index` is at simulated time `time_s`.
  Eigen::Vector2d person_position(std::size_t index, double time_s) const;
};

struct WorldLoad {
  World world;
  std::vector<std::string> errors;  // each names the file and the key: "lab.yaml: walls[3].points: ..."
  bool ok() const { return errors.empty(); }
  std::string error_text() const;
};

// Reads a world file. Unknown keys, wrong types, out-of-range values and open or degenerate
// polygons are errors.
WorldLoad load_world(const std::string& path);
// The same from text; `name` stands for the file in messages.
WorldLoad load_world_text(const std::string& yaml, const std::string& name);

// Point-in-polygon (even-odd rule) for a polygon without the repeated closing vertex.
bool polygon_contains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& point);

}  // namespace stereoscout::host_sim
