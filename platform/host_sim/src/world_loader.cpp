// Reads world files (docs/worlds.md). Start-up code: it may allocate and report errors
// freely; every error names the file and the key path.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "stereoscout/core/config.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/host_sim/textures.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::host_sim {
namespace {

using Points = std::vector<Eigen::Vector2d>;

constexpr const char* kSurfaceKeys[] = {"texture", "brightness", "contrast"};
constexpr double kClosingTolerance_m = 1e-6;

std::string describe_node(const cv::FileNode& node) {
  if (node.isMap()) return "a map";
  if (node.isSeq()) return "a list";
  if (node.isString()) return "text '" + static_cast<std::string>(node) + "'";
  if (node.isInt() || node.isReal()) return "a number";
  return "nothing";
}

class WorldParser {
 public:
  WorldParser(std::string file, std::vector<std::string>& errors) : file_(std::move(file)), errors_(errors) {}

  void error(const std::string& path, const std::string& message) {
    errors_.push_back(file_ + ": " + path + ": " + message);
  }

  // Reports keys of `map` outside `allowed` (plus the surface keys when `surface` is set).
  void check_keys(const cv::FileNode& map, const std::string& path, std::initializer_list<const char*> allowed,
                  bool surface) {
    const std::vector<std::string> keys = map.keys();
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const std::string& key = keys[i];
      if (std::find(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(i), key) != keys.begin() + static_cast<std::ptrdiff_t>(i)) {
        error(join(path, key), "key given more than once");
        continue;
      }
      const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* k) { return key == k; }) ||
                         (surface && std::any_of(std::begin(kSurfaceKeys), std::end(kSurfaceKeys),
                                                 [&](const char* k) { return key == k; }));
      if (!known) {
        error(join(path, key), "unknown key");
      }
    }
  }

  bool number(const cv::FileNode& map, const std::string& path, const char* key, double& value, double min,
              double max, bool required) {
    const cv::FileNode node = map[key];
    if (node.empty() || node.isNone()) {
      if (required) error(join(path, key), "missing (a number is required)");
      return false;
    }
    if (!node.isInt() && !node.isReal()) {
      error(join(path, key), "expected a number, got " + describe_node(node));
      return false;
    }
    const double read = static_cast<double>(node);
    if (!(read >= min && read <= max)) {
      std::ostringstream message;
      message << "value " << read << " out of range [" << min << ", " << max << "]";
      error(join(path, key), message.str());
      return false;
    }
    value = read;
    return true;
  }

  bool text(const cv::FileNode& map, const std::string& path, const char* key, std::string& value, bool required) {
    const cv::FileNode node = map[key];
    if (node.empty() || node.isNone()) {
      if (required) error(join(path, key), "missing (text is required)");
      return false;
    }
    if (!node.isString()) {
      error(join(path, key), "expected text, got " + describe_node(node));
      return false;
    }
    value = static_cast<std::string>(node);
    return true;
  }

  // A fixed-length list of numbers, e.g. a point [x, y] or a range [z_min, z_max].
  bool numbers(const cv::FileNode& node, const std::string& path, double* values, int count) {
    if (!node.isSeq() || static_cast<int>(node.size()) != count) {
      error(path, "expected a list of " + std::to_string(count) + " numbers, got " + describe_node(node));
      return false;
    }
    for (int i = 0; i < count; ++i) {
      const cv::FileNode entry = node[i];
      if (!entry.isInt() && !entry.isReal()) {
        error(path + "[" + std::to_string(i) + "]", "expected a number, got " + describe_node(entry));
        return false;
      }
      values[i] = static_cast<double>(entry);
    }
    return true;
  }

  bool point(const cv::FileNode& map, const std::string& path, const char* key, Eigen::Vector2d& value) {
    double xy[2] = {0.0, 0.0};
    if (map[key].empty()) {
      error(join(path, key), "missing (a point [x, y] is required)");
      return false;
    }
    if (!numbers(map[key], join(path, key), xy, 2)) return false;
    value = {xy[0], xy[1]};
    return true;
  }

  bool z_range(const cv::FileNode& map, const std::string& path, double& z_min, double& z_max) {
    double z[2] = {0.0, 0.0};
    if (map["z"].empty()) {
      error(join(path, "z"), "missing (a height range [z_min, z_max] is required)");
      return false;
    }
    if (!numbers(map["z"], join(path, "z"), z, 2)) return false;
    if (!(z[0] >= 0.0 && z[1] > z[0] && z[1] <= 100.0)) {
      error(join(path, "z"), "needs 0 <= z_min < z_max");
      return false;
    }
    z_min = z[0];
    z_max = z[1];
    return true;
  }

  bool point_list(const cv::FileNode& map, const std::string& path, const char* key, Points& points,
                  std::size_t min_count) {
    const cv::FileNode node = map[key];
    const std::string key_path = join(path, key);
    if (!node.isSeq()) {
      error(key_path, "expected a list of points [[x, y], ...], got " + describe_node(node));
      return false;
    }
    points.clear();
    for (std::size_t i = 0; i < node.size(); ++i) {
      double xy[2] = {0.0, 0.0};
      if (!numbers(node[static_cast<int>(i)], key_path + "[" + std::to_string(i) + "]", xy, 2)) return false;
      points.emplace_back(xy[0], xy[1]);
    }
    if (points.size() < min_count) {
      error(key_path, "needs at least " + std::to_string(min_count) + " points");
      return false;
    }
    return true;
  }

  // A polygon is written closed: its last point repeats the first. The closing point is dropped.
  bool polygon(const cv::FileNode& map, const std::string& path, const char* key, Points& points) {
    if (!point_list(map, path, key, points, 4)) return false;
    if ((points.front() - points.back()).norm() > kClosingTolerance_m) {
      error(join(path, key), "open polygon: the last point must repeat the first");
      return false;
    }
    points.pop_back();
    if (std::abs(signed_area(points)) < 1e-6) {
      error(join(path, key), "degenerate polygon (zero area)");
      return false;
    }
    return true;
  }

  void surface(const cv::FileNode& map, const std::string& path, Surface& value) {
    std::string name;
    if (text(map, path, "texture", name, false)) {
      const auto* found = std::find_if(std::begin(kTextureNames), std::end(kTextureNames),
                                       [&](const char* n) { return name == n; });
      if (found == std::end(kTextureNames)) {
        error(join(path, "texture"), "unknown texture '" + name + "' (blank, low, noise, brick, wood, poster, books, tile, carpet)");
      } else {
        value.texture = static_cast<Texture>(found - std::begin(kTextureNames));
      }
    }
    double brightness = value.brightness;
    double contrast = value.contrast;
    if (number(map, path, "brightness", brightness, 0.0, 20.0, false)) value.brightness = static_cast<float>(brightness);
    if (number(map, path, "contrast", contrast, 0.0, 2.0, false)) value.contrast = static_cast<float>(contrast);
    // Each surface starts at its own place in the texture tile (seeded, deterministic).
    core::RandomStream random(seed_, {core::stream_purpose::sim_world, surface_count_++, 0});
    value.texture_offset_u_m = static_cast<float>(random.uniform(0.0, 100.0));
    value.texture_offset_v_m = static_cast<float>(random.uniform(0.0, 100.0));
  }

  bool floor_type(const cv::FileNode& map, const std::string& path, FloorType& value) {
    std::string name;
    if (!text(map, path, "type", name, false)) return false;
    if (name == "tile") {
      value = FloorType::tile;
    } else if (name == "carpet") {
      value = FloorType::carpet;
    } else {
      error(join(path, "type"), "unknown floor type '" + name + "' (tile, carpet)");
      return false;
    }
    return true;
  }

  // Iterates a top-level list of maps, calling `item(node, path)` for each.
  template <class Item>
  void each(const cv::FileNode& root, const std::string& parent, const char* key, Item item) {
    const cv::FileNode list = root[key];
    if (list.empty() || list.isNone()) return;
    if (!list.isSeq()) {
      error(join(parent, key), "expected a list, got " + describe_node(list));
      return;
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      const cv::FileNode node = list[static_cast<int>(i)];
      const std::string path = join(parent, key) + "[" + std::to_string(i) + "]";
      if (!node.isMap()) {
        error(path, "expected a map of keys, got " + describe_node(node));
        continue;
      }
      item(node, path);
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  static double signed_area(const Points& points) {
    double area = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d& p = points[i];
      const Eigen::Vector2d& q = points[(i + 1) % points.size()];
      area += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * area;
  }

  std::uint64_t seed_ = 1;

 private:
  std::string file_;
  std::vector<std::string>& errors_;
  std::uint32_t surface_count_ = 0;
};

struct Opening {
  double at = 0.0;
  double width = 0.9;
  double bottom = 0.0;
  double top = 2.0;
  bool window = false;
  double brightness = 3.0;
};

// Splits one wall segment around the openings that overlap it. `start_m` is the distance of
// `a` along the whole wall polyline; the texture continues across segments.
void add_wall_segment(World& world, const WallPiece& prototype, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      double start_m, const std::vector<Opening>& openings) {
  const double length = (b - a).norm();
  auto piece = [&](double from, double to, double z_min, double z_max, const Surface& surface) {
    if (to - from <= 1e-9 || z_max - z_min <= 1e-9) return;
    WallPiece wall = prototype;
    wall.a = a + (b - a) * ((from - start_m) / length);
    wall.b = a + (b - a) * ((to - start_m) / length);
    wall.z_min = z_min;
    wall.z_max = z_max;
    wall.texture_u0_m = from;
    wall.surface = surface;
    world.walls.push_back(wall);
  };
  double cursor = start_m;
  const double end = start_m + length;
  for (const Opening& opening : openings) {
    const double from = std::max(opening.at - 0.5 * opening.width, start_m);
    const double to = std::min(opening.at + 0.5 * opening.width, end);
    if (to <= from) continue;
    piece(cursor, from, prototype.z_min, prototype.z_max, prototype.surface);
    piece(from, to, prototype.z_min, opening.bottom, prototype.surface);
    piece(from, to, opening.top, prototype.z_max, prototype.surface);
    if (!opening.window && opening.bottom <= 0.0) {
      world.doorways.push_back(Doorway{a + (b - a) * ((from - start_m) / length), a + (b - a) * ((to - start_m) / length)});
    }
    if (opening.window) {
      Surface glass;
      glass.texture = Texture::blank;
      glass.brightness = static_cast<float>(opening.brightness);
      glass.contrast = 0.0F;
      piece(from, to, opening.bottom, opening.top, glass);
    }
    cursor = to;
  }
  piece(cursor, end, prototype.z_min, prototype.z_max, prototype.surface);
}

void read_walls(WorldParser& parser, const cv::FileNode& root, World& world) {
  parser.each(root, "", "walls", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"points", "height", "openings"}, true);
    Points points;
    WallPiece prototype;
    prototype.z_max = world.ceiling_height;
    parser.number(node, path, "height", prototype.z_max, 0.01, 100.0, false);
    parser.surface(node, path, prototype.surface);
    if (!parser.point_list(node, path, "points", points, 2)) return;
    std::vector<Opening> openings;
    parser.each(node, path, "openings", [&](const cv::FileNode& o, const std::string& opening_path) {
      parser.check_keys(o, opening_path, {"at", "width", "bottom", "top", "kind", "brightness"}, false);
      Opening opening;
      std::string kind = "door";
      parser.number(o, opening_path, "at", opening.at, 0.0, 1e4, true);
      parser.number(o, opening_path, "width", opening.width, 0.01, 100.0, true);
      parser.number(o, opening_path, "bottom", opening.bottom, 0.0, 100.0, false);
      parser.number(o, opening_path, "top", opening.top, 0.0, 100.0, false);
      parser.number(o, opening_path, "brightness", opening.brightness, 0.0, 20.0, false);
      if (parser.text(o, opening_path, "kind", kind, false) && kind != "door" && kind != "window") {
        parser.error(opening_path + ".kind", "unknown kind '" + kind + "' (door, window)");
      }
      opening.window = kind == "window";
      if (opening.top <= opening.bottom) parser.error(opening_path + ".top", "must be above bottom");
      openings.push_back(opening);
    });
    std::sort(openings.begin(), openings.end(), [](const Opening& l, const Opening& r) { return l.at < r.at; });
    double start_m = 0.0;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      const double length = (points[i + 1] - points[i]).norm();
      if (length < 1e-9) {
        parser.error(path + ".points[" + std::to_string(i + 1) + "]", "repeats the previous point");
        return;
      }
      add_wall_segment(world, prototype, points[i], points[i + 1], start_m, openings);
      start_m += length;
    }
  });
}

void read_solids(WorldParser& parser, const cv::FileNode& root, World& world) {
  parser.each(root, "", "prisms", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"polygon", "z"}, true);
    Prism prism;
    parser.surface(node, path, prism.surface);
    if (parser.polygon(node, path, "polygon", prism.polygon) && parser.z_range(node, path, prism.z_min, prism.z_max)) {
      world.prisms.push_back(prism);
    }
  });
  parser.each(root, "", "boxes", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"center", "size", "yaw_deg", "z"}, true);
    Prism prism;
    Eigen::Vector2d center;
    double size[2] = {0.0, 0.0};
    double yaw_deg = 0.0;
    parser.surface(node, path, prism.surface);
    parser.number(node, path, "yaw_deg", yaw_deg, -360.0, 360.0, false);
    const bool sized = !node["size"].empty() && parser.numbers(node["size"], path + ".size", size, 2);
    if (node["size"].empty()) parser.error(path + ".size", "missing (a size [x, y] is required)");
    if (!parser.point(node, path, "center", center) || !sized || !parser.z_range(node, path, prism.z_min, prism.z_max)) return;
    if (size[0] <= 0.0 || size[1] <= 0.0) {
      parser.error(path + ".size", "must be positive");
      return;
    }
    const core::Pose2 pose{center.x(), center.y(), core::degrees_to_radians(yaw_deg)};
    const double hx = 0.5 * size[0];
    const double hy = 0.5 * size[1];
    for (const Eigen::Vector2d& corner : {Eigen::Vector2d(-hx, -hy), Eigen::Vector2d(hx, -hy), Eigen::Vector2d(hx, hy),
                                         Eigen::Vector2d(-hx, hy)}) {
      prism.polygon.push_back(pose.transform_point(corner));
    }
    world.prisms.push_back(prism);
  });
  parser.each(root, "", "cylinders", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"center", "radius", "z"}, true);
    Cylinder cylinder;
    parser.surface(node, path, cylinder.surface);
    if (parser.point(node, path, "center", cylinder.center) &&
        parser.number(node, path, "radius", cylinder.radius, 0.005, 50.0, true) &&
        parser.z_range(node, path, cylinder.z_min, cylinder.z_max)) {
      world.cylinders.push_back(cylinder);
    }
  });
}

void read_people_and_regions(WorldParser& parser, const cv::FileNode& root, World& world) {
  parser.each(root, "", "people", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"waypoints", "speed", "radius", "height"}, true);
    Person person;
    parser.surface(node, path, person.surface);
    parser.number(node, path, "speed", person.speed_mps, 0.0, 5.0, false);
    parser.number(node, path, "radius", person.radius, 0.05, 2.0, false);
    parser.number(node, path, "height", person.height, 0.1, 3.0, false);
    if (parser.point_list(node, path, "waypoints", person.waypoints, 1)) world.people.push_back(person);
  });
  parser.each(root, "", "floor_regions", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"polygon", "type"}, true);
    FloorRegion region;
    region.surface = world.floor;
    parser.floor_type(node, path, region.type);
    parser.surface(node, path, region.surface);
    if (parser.polygon(node, path, "polygon", region.polygon)) world.floor_regions.push_back(region);
  });
  parser.each(root, "", "lights", [&](const cv::FileNode& node, const std::string& path) {
    parser.check_keys(node, path, {"polygon", "gain"}, false);
    LightRegion light;
    parser.number(node, path, "gain", light.gain, 0.0, 20.0, true);
    if (parser.polygon(node, path, "polygon", light.polygon)) world.lights.push_back(light);
  });
}

void read_top_level(WorldParser& parser, const cv::FileNode& root, World& world) {
  parser.check_keys(root, "",
                    {"name", "seed", "texture_variants", "ceiling_height", "start", "floor", "ceiling", "walls", "prisms", "boxes",
                     "cylinders", "people", "floor_regions", "lights"},
                    false);
  parser.text(root, "", "name", world.name, false);
  double seed = 1.0;
  if (parser.number(root, "", "seed", seed, 0.0, 2147483647.0, false)) world.texture_seed = static_cast<std::uint64_t>(seed);
  parser.seed_ = world.texture_seed;
  double variants = 1.0;
  if (parser.number(root, "", "texture_variants", variants, 1.0, TextureBank::kMaxVariants, false)) {
    if (variants == std::floor(variants)) {
      world.texture_variants = static_cast<int>(variants);
    } else {
      parser.error("texture_variants", "expected a whole number of tiles, got " + core::format_number(variants));
    }
  }
  parser.number(root, "", "ceiling_height", world.ceiling_height, 0.5, 100.0, false);
  double start[3] = {0.0, 0.0, 0.0};
  if (root["start"].empty()) {
    parser.error("start", "missing (the robot's start pose [x, y, theta_deg] is required)");
  } else if (parser.numbers(root["start"], "start", start, 3)) {
    world.start = core::Pose2{start[0], start[1], core::wrap_angle(core::degrees_to_radians(start[2]))};
  }
  world.floor = Surface{Texture::tile, 0.5F, 0.5F, 0.0F, 0.0F};
  world.ceiling = Surface{Texture::low, 0.8F, 0.1F, 0.0F, 0.0F};
  for (const char* key : {"floor", "ceiling"}) {
    const cv::FileNode node = root[key];
    if (node.empty() || node.isNone()) continue;
    if (!node.isMap()) {
      parser.error(key, "expected a map of keys, got " + describe_node(node));
      continue;
    }
    const bool is_floor = std::string(key) == "floor";
    parser.check_keys(node, key, is_floor ? std::initializer_list<const char*>{"type"} : std::initializer_list<const char*>{}, true);
    if (is_floor) parser.floor_type(node, key, world.floor_type);
    parser.surface(node, key, is_floor ? world.floor : world.ceiling);
  }
}

}  // namespace

std::string WorldLoad::error_text() const {
  std::string text;
  for (const std::string& error : errors) text += error + "\n";
  return text;
}

WorldLoad load_world_text(const std::string& yaml, const std::string& name) {
  WorldLoad load;
  load.world.file = name;
  WorldParser parser(name, load.errors);
  // cv::FileStorage insists on a "%YAML:1.0" first line; world files are plain YAML.
  const std::string document = yaml.rfind("%YAML", 0) == 0 ? yaml : "%YAML:1.0\n" + yaml;
  cv::FileStorage storage;
  try {
    storage.open(document, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& error) {
    load.errors.push_back(name + ": not valid YAML (" + error.err + ")");
    return load;
  }
  const cv::FileNode root = storage.root();
  if (!storage.isOpened() || !root.isMap()) {
    load.errors.push_back(name + ": not valid YAML or not a map of keys at the top level");
    return load;
  }
  read_top_level(parser, root, load.world);
  read_walls(parser, root, load.world);
  read_solids(parser, root, load.world);
  read_people_and_regions(parser, root, load.world);
  if (load.ok() && load.world.walls.empty() && load.world.prisms.empty()) {
    load.errors.push_back(name + ": walls: a world needs at least one wall or prism");
  }
  return load;
}

WorldLoad load_world(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) {
    WorldLoad load;
    load.errors.push_back(path + ": cannot open the world file");
    return load;
  }
  std::stringstream text;
  text << stream.rdbuf();
  return load_world_text(text.str(), path);
}

}  // namespace stereoscout::host_sim
