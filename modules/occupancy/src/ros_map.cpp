#include "stereoscout/occupancy/ros_map.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace stereoscout::occupancy {
namespace {

std::string trim(const std::string& text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin])) != 0) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1])) != 0) --end;
  return text.substr(begin, end - begin);
}

std::string unquote(const std::string& text) {
  if (text.size() >= 2 && (text.front() == '"' || text.front() == '\'') && text.back() == text.front()) {
    return text.substr(1, text.size() - 2);
  }
  return text;
}

bool parse_number(const std::string& text, double& value) {
  const std::string cleaned = trim(text);
  if (cleaned.empty()) return false;
  char* end = nullptr;
  value = std::strtod(cleaned.c_str(), &end);
  return end == cleaned.c_str() + cleaned.size();
}

bool parse_origin(const std::string& text, double& x, double& y) {
  const std::string cleaned = trim(text);
  if (cleaned.size() < 2 || cleaned.front() != '[' || cleaned.back() != ']') return false;
  std::stringstream items(cleaned.substr(1, cleaned.size() - 2));
  std::string item;
  double values[3] = {0.0, 0.0, 0.0};
  int count = 0;
  while (std::getline(items, item, ',')) {
    if (count == 3 || !parse_number(item, values[count])) return false;
    ++count;
  }
  x = values[0];
  y = values[1];
  return count == 3;
}

std::string folder_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string file_name_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// PGM header token, skipping whitespace and '#' comments.
bool read_pgm_token(std::istream& in, std::string& token) {
  token.clear();
  int ch = in.get();
  while (ch != EOF) {
    if (ch == '#') {
      while (ch != EOF && ch != '\n') ch = in.get();
    } else if (std::isspace(ch) != 0) {
      ch = in.get();
    } else {
      break;
    }
  }
  while (ch != EOF && std::isspace(ch) == 0) {
    token.push_back(static_cast<char>(ch));
    ch = in.get();
  }
  return !token.empty();  // the single whitespace after the last header token is consumed
}

CellState classify_pixel(std::uint8_t value, const RosMap& map) {
  const double probability = map.negate ? value / 255.0 : (255.0 - value) / 255.0;
  if (probability > map.occupied_thresh) return CellState::occupied;
  if (probability < map.free_thresh) return CellState::free;
  return CellState::unknown;
}

}  // namespace

RosMap classify_grid(const OccupancyGrid& grid, const CellThresholds& thresholds) {
  RosMap map;
  map.geometry = grid.geometry();
  map.occupied_thresh = thresholds.occupied;
  map.free_thresh = thresholds.free;
  map.cells.resize(map.geometry.cell_count());
  classify_cells(grid, thresholds, map.cells.data());
  return map;
}

std::string write_ros_map(const RosMap& map, const std::string& pgm_path, const std::string& yaml_path) {
  std::FILE* pgm = std::fopen(pgm_path.c_str(), "wb");
  if (pgm == nullptr) return "cannot write " + pgm_path;
  const int width = map.geometry.width_cells;
  std::fprintf(pgm, "P5\n# stereoscout occupancy grid, resolution %g m\n%d %d\n255\n", map.geometry.resolution_m,
               width, map.geometry.height_cells);
  std::vector<unsigned char> row(static_cast<std::size_t>(width));
  for (int y = map.geometry.height_cells - 1; y >= 0; --y) {  // image top = highest y
    for (int x = 0; x < width; ++x) {
      const CellState state = map.at(x, y);
      row[static_cast<std::size_t>(x)] =
          state == CellState::occupied ? kPgmOccupied : state == CellState::free ? kPgmFree : kPgmUnknown;
    }
    std::fwrite(row.data(), 1, row.size(), pgm);
  }
  if (std::fclose(pgm) != 0) return "error writing " + pgm_path;

  std::FILE* yaml = std::fopen(yaml_path.c_str(), "w");
  if (yaml == nullptr) return "cannot write " + yaml_path;
  std::fprintf(yaml,
               "image: %s\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\noccupied_thresh: %.6g\n"
               "free_thresh: %.6g\n",
               file_name_of(pgm_path).c_str(), map.geometry.resolution_m, map.geometry.origin_x_m,
               map.geometry.origin_y_m, map.occupied_thresh, map.free_thresh);
  if (std::fclose(yaml) != 0) return "error writing " + yaml_path;
  return {};
}

std::string read_ros_map(const std::string& yaml_path, RosMap& map) {
  std::ifstream in(yaml_path);
  if (!in) return "cannot read " + yaml_path;
  map = RosMap{};
  std::string image;
  bool has_resolution = false;
  bool has_origin = false;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::size_t hash = line.find('#');
    const std::string content = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (content.empty()) continue;
    const std::size_t colon = content.find(':');
    const std::string where = yaml_path + ":" + std::to_string(line_number);
    if (colon == std::string::npos) return where + ": expected 'key: value'";
    const std::string key = trim(content.substr(0, colon));
    const std::string value = trim(content.substr(colon + 1));
    double number = 0.0;
    if (key == "image") {
      image = unquote(value);
    } else if (key == "resolution") {
      if (!parse_number(value, map.geometry.resolution_m) || !(map.geometry.resolution_m > 0.0)) {
        return where + ": resolution must be a positive number";
      }
      has_resolution = true;
    } else if (key == "origin") {
      if (!parse_origin(value, map.geometry.origin_x_m, map.geometry.origin_y_m)) {
        return where + ": origin must be [x, y, yaw]";
      }
      has_origin = true;
    } else if (key == "negate" || key == "occupied_thresh" || key == "free_thresh") {
      if (!parse_number(value, number)) return where + ": " + key + " must be a number";
      if (key == "negate") map.negate = number != 0.0;
      if (key == "occupied_thresh") map.occupied_thresh = number;
      if (key == "free_thresh") map.free_thresh = number;
    }  // other map_server keys (mode, ...) do not change the classification we use
  }
  if (image.empty()) return yaml_path + ": missing key 'image'";
  if (!has_resolution) return yaml_path + ": missing key 'resolution'";
  if (!has_origin) return yaml_path + ": missing key 'origin'";
  const std::string pgm_path = !image.empty() && image.front() == '/' ? image : folder_of(yaml_path) + image;
  return read_pgm_cells(pgm_path, map);
}

std::string read_pgm_cells(const std::string& pgm_path, RosMap& map) {
  std::ifstream in(pgm_path, std::ios::binary);
  if (!in) return "cannot read " + pgm_path;
  std::string magic;
  std::string width_text;
  std::string height_text;
  std::string max_text;
  if (!read_pgm_token(in, magic) || magic != "P5") return pgm_path + ": not a binary PGM (P5)";
  if (!read_pgm_token(in, width_text) || !read_pgm_token(in, height_text) || !read_pgm_token(in, max_text)) {
    return pgm_path + ": truncated header";
  }
  const long width = std::strtol(width_text.c_str(), nullptr, 10);
  const long height = std::strtol(height_text.c_str(), nullptr, 10);
  const long max_value = std::strtol(max_text.c_str(), nullptr, 10);
  if (width <= 0 || height <= 0 || width > 100000 || height > 100000) return pgm_path + ": bad image size";
  if (max_value != 255) return pgm_path + ": only 8-bit PGM (maxval 255) is supported";
  map.geometry.width_cells = static_cast<int>(width);
  map.geometry.height_cells = static_cast<int>(height);
  std::vector<unsigned char> pixels(map.geometry.cell_count());
  in.read(reinterpret_cast<char*>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
  if (static_cast<std::size_t>(in.gcount()) != pixels.size()) return pgm_path + ": truncated pixel data";
  map.cells.resize(pixels.size());
  const std::size_t row_length = static_cast<std::size_t>(width);
  for (long image_row = 0; image_row < height; ++image_row) {
    const std::size_t map_row = static_cast<std::size_t>(height - 1 - image_row);  // top row = highest y
    for (std::size_t x = 0; x < row_length; ++x) {
      map.cells[map_row * row_length + x] =
          classify_pixel(pixels[static_cast<std::size_t>(image_row) * row_length + x], map);
    }
  }
  return {};
}

}  // namespace stereoscout::occupancy
