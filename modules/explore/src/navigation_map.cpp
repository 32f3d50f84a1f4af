#include "stereoscout/explore/navigation_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "stereoscout/core/config/grid.hpp"

namespace stereoscout::explore {
namespace {

constexpr double kNoSiteDistance_m = 1e9;
constexpr double kDiagonal = 1.4142135623730951;
// The four 4-neighbours of a cell, as (dx, dy).
constexpr int kAxisSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
// The eight 8-neighbours of a cell, as (dx, dy).
constexpr int kNeighbourSteps[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
// object_size_ of an occupied cell: its component's size, while find_shadows runs.
constexpr std::uint8_t kSizeUnmeasured = 0;
constexpr std::uint8_t kSizeMeasuring = 1;
constexpr std::uint8_t kSizeObject = 2;
constexpr std::uint8_t kSizeLarger = 3;

// A distance transform's site is its cell's coordinates packed in one word (x in the low 16
// bits), so that distances need no division. "None" is a site far outside any grid of at most
// kMaxSide cells a side (the config's limit): farther from every cell than any real site, so
// the transform needs no test for it.
constexpr int kMaxSide = core::kMaxGridSideCells;
constexpr std::int32_t kNoSite = 0x7fffffff;  // x 65535, y 32767
constexpr std::int64_t kMaxSideSquared = std::int64_t{kMaxSide} * kMaxSide;
static_assert(kMaxSide < (1 << 15), "packed coordinates take 15 bits each");
static_assert(std::int64_t{(1 << 16) - kMaxSide} * ((1 << 16) - kMaxSide) > 2 * kMaxSideSquared,
              "no site must lie farther from every cell than any real site");
std::int32_t pack_site(int x, int y) { return static_cast<std::int32_t>((y << 16) | x); }
int site_x(std::int32_t site) { return site & 0xffff; }
int site_y(std::int32_t site) { return site >> 16; }
std::int64_t site_distance2(std::int32_t site, int x, int y) {
  const std::int64_t dx = site_x(site) - x;
  const std::int64_t dy = site_y(site) - y;
  return dx * dx + dy * dy;
}

// The first and last cell of a row that is not unknown (-1: none), skipping unknown cells
// eight at a time (unknown is 0): most of the grid is unknown, and the window is found anew
// at every rebuild.
static_assert(static_cast<std::uint8_t>(CellState::unknown) == 0);
constexpr int kWord = 8;
bool all_unknown(const std::uint8_t* cells) {
  std::uint64_t word = 0;
  std::memcpy(&word, cells, kWord);
  return word == 0;
}
int first_known(const std::uint8_t* row, int width) {
  int x = 0;
  while (x + kWord <= width && all_unknown(row + x)) x += kWord;
  for (; x < width; ++x) {
    if (row[x] != 0) return x;
  }
  return -1;
}
int last_known(const std::uint8_t* row, int width) {
  int x = width;
  while (x - kWord >= 0 && all_unknown(row + x - kWord)) x -= kWord;
  for (--x; x >= 0; --x) {
    if (row[x] != 0) return x;
  }
  return -1;
}

int cells_for(double metres, double resolution_m) { return static_cast<int>(std::ceil(metres / resolution_m)) + 1; }
// Whole cells in a length (0.6 m is 6 cells of 0.1 m, despite rounding).
int whole_cells(double metres, double resolution_m) {
  return static_cast<int>(std::floor(metres / resolution_m + 1e-9));
}

}  // namespace

NavigationMap::NavigationMap(const ExploreParams& params)
    : params_(params),
      capacity_(static_cast<std::size_t>(params.max_width) * static_cast<std::size_t>(params.max_height)),
      occupied_site_(new std::int32_t[capacity_]),
      unknown_site_(new std::int32_t[capacity_]),
      traversability_(new std::uint8_t[capacity_]),
      penalty_(new float[capacity_]),
      reached_stamp_(new std::uint32_t[capacity_]()),
      reach_steps_(new std::int32_t[capacity_]()),
      queue_(new std::int32_t[capacity_]),
      region_label_(new std::uint32_t[capacity_]()),
      shadow_(new std::uint8_t[capacity_]()),
      object_size_(new std::uint8_t[capacity_]()) {}

bool NavigationMap::rebuild(const GridView& grid, const Eigen::Vector2d& robot, const Eigen::Vector2d& extra) {
  grid_ = grid;
  window_ = CellBox{};
  ++reach_stamp_;  // forget the previous flood fill
  if (grid.cells == nullptr || grid.width <= 0 || grid.height <= 0 || grid.width > kMaxSide ||
      grid.height > kMaxSide || static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height) > capacity_) {
    grid_.width = 0;
    grid_.height = 0;
    return false;
  }
  find_window(robot, extra);
  robot_ = robot;
  extra_unknown_centre_ = extra;
  find_shadows();
  distance_transform(occupied_site_.get(), [this](int x, int y) { return obstacle_site(x, y); });
  distance_transform(unknown_site_.get(), [this](int x, int y) { return grid_.at(x, y) == CellState::unknown; });
  classify();
  open_way_out();
  find_pockets();
  return true;
}

// The robot stands where its disc is: when an obstacle cell lies inside it, short of deep (a
// person who walked into the robot, a grazed jamb, a pose correction), its own cell and every
// neighbour are lethal, and no plan could leave. Then the cells under the disc that are lethal
// only for their clearance, and no nearer an obstacle than the robot's own cell, become
// passable at the highest obstacle cost: plans lead out away from the cell (a plan past it
// would have the safety check stop the robot, which never moves deeper into a cell it
// overlaps). Nothing changes while the robot's own cell is passable.
void NavigationMap::open_way_out() {
  const Eigen::Vector2i robot = grid_.cell_of(robot_);
  if (!window_.contains(robot.x(), robot.y()) || passable(robot.x(), robot.y())) return;
  const double clearance = occupied_distance_m(robot.x(), robot.y());
  const int reach = static_cast<int>(std::ceil(params_.robot_radius_m / grid_.resolution_m));
  const double radius2 = params_.robot_radius_m * params_.robot_radius_m;
  for (int y = robot.y() - reach; y <= robot.y() + reach; ++y) {
    for (int x = robot.x() - reach; x <= robot.x() + reach; ++x) {
      if (!window_.contains(x, y) || (grid_.center(x, y) - robot_).squaredNorm() > radius2) continue;
      if (obstacle_site(x, y) || (grid_.at(x, y) == CellState::unknown && !unknown_passable(x, y)) ||
          occupied_distance_m(x, y) < clearance) {
        continue;
      }
      traversability_[index(x, y)] = static_cast<std::uint8_t>(Traversability::inflated);
    }
  }
}

std::size_t NavigationMap::open_trail(const TrailMemory& trail) {
  if (grid_.width <= 0) return 0;
  // Steps of a quarter cell along each driven segment: consecutive cells are 8-neighbours.
  const double step_m = 0.25 * grid_.resolution_m;
  std::size_t opened = 0;
  for (std::size_t i = 0; i < trail.size(); ++i) {
    const Eigen::Vector2d& to = trail[i].position;
    if (i == 0 || !trail[i].joined) {
      if (open_trail_cell(to)) ++opened;
      continue;
    }
    const Eigen::Vector2d& from = trail[i - 1].position;
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / step_m)));
    for (int k = 1; k <= steps; ++k) {
      if (open_trail_cell(from + (to - from) * (static_cast<double>(k) / steps))) ++opened;
    }
  }
  return opened;
}

// Occupied cells (and unknown ones kept clear of) stay closed, and so do cells whose disc
// would touch an occupied cell: the safety check would stop the robot there.
bool NavigationMap::open_trail_cell(const Eigen::Vector2d& position) {
  const Eigen::Vector2i cell = grid_.cell_of(position);
  const int x = cell.x();
  const int y = cell.y();
  if (!window_.contains(x, y) || passable(x, y) || obstacle_site(x, y) ||
      occupied_distance_m(x, y) < params_.robot_radius_m) {
    return false;
  }
  traversability_[index(x, y)] = static_cast<std::uint8_t>(Traversability::inflated);
  return true;
}

// Breadth-first from `seed` (marked by the caller) over the fixed queue: `visit(x, y)` for
// each cell taken, `enter(nx, ny, from)` for each neighbour by `steps`, which marks it and
// returns true to queue it. Returns how many cells were queued; they stay in queue_.
template <std::size_t kSteps, typename Enter, typename Visit>
std::size_t NavigationMap::breadth_first(std::size_t seed, const int (&steps)[kSteps][2], Enter&& enter,
                                         Visit&& visit) {
  std::size_t head = 0;
  std::size_t tail = 0;
  queue_[tail++] = static_cast<std::int32_t>(seed);
  while (head < tail) {
    const auto cell = static_cast<std::size_t>(queue_[head++]);
    const int x = static_cast<int>(cell % static_cast<std::size_t>(grid_.width));
    const int y = static_cast<int>(cell / static_cast<std::size_t>(grid_.width));
    visit(x, y);
    for (const auto& step : steps) {
      const int nx = x + step[0];
      const int ny = y + step[1];
      if (enter(nx, ny, cell)) queue_[tail++] = static_cast<std::int32_t>(index(nx, ny));
    }
  }
  return tail;
}

void NavigationMap::find_pockets() {
  region_stamp_ += 2;
  pocket_cells_ = 0;
  for (int y = window_.y0; y < window_.y1; ++y) {
    for (int x = window_.x0; x < window_.x1; ++x) {
      const std::size_t i = index(x, y);
      if (grid_.at(x, y) == CellState::unknown && region_label_[i] < region_stamp_) label_region(i);
    }
  }
}

bool NavigationMap::label_region(std::size_t seed) {
  const double cell_area = grid_.resolution_m * grid_.resolution_m;
  const auto max_cells = static_cast<std::size_t>(params_.explore.max_pocket_area_m2 / cell_area);
  bool open = false;  // reaches the window's edge: part of the unexplored world outside
  region_label_[seed] = region_stamp_;
  const std::size_t tail = breadth_first(
      seed, kAxisSteps,
      [&](int nx, int ny, std::size_t) {
        if (!window_.contains(nx, ny)) {
          open = true;
          return false;
        }
        std::uint32_t& label = region_label_[index(nx, ny)];
        if (grid_.at(nx, ny) != CellState::unknown || label >= region_stamp_) return false;
        label = region_stamp_;
        return true;
      },
      [](int, int) {});
  if (open || tail > max_cells) return false;
  for (std::size_t k = 0; k < tail; ++k) region_label_[static_cast<std::size_t>(queue_[k])] = region_stamp_ + 1;
  pocket_cells_ += tail;
  return true;
}

// The camera sees an obstacle's near face; what lies behind it stays unknown until a view from
// elsewhere, and near the robot unknown cells are passable. Behind each occupied cell with a
// free 4-neighbour, the unknown cells straight on from that neighbour, up to shadow_depth_m,
// are taken as the obstacle's body. Along the axes only: a diagonal shadow from a jamb's end
// would fall across the door it bounds. Never under the robot's disc (it stands there). Only
// behind an object (a component no larger than shadow_object_max_m): a wall's far side is a
// room or corridor, and a shadow there narrows the way in beside a door.
void NavigationMap::find_shadows() {
  shadow_cells_ = 0;
  const int depth = whole_cells(params_.explore.shadow_depth_m, grid_.resolution_m);
  if (depth <= 0) return;  // nothing was ever marked
  for (int y = window_.y0; y < window_.y1; ++y) {
    std::fill(shadow_.get() + index(window_.x0, y), shadow_.get() + index(window_.x1 - 1, y) + 1, std::uint8_t{0});
    std::fill(object_size_.get() + index(window_.x0, y), object_size_.get() + index(window_.x1 - 1, y) + 1,
              kSizeUnmeasured);
  }
  const double radius2 = params_.robot_radius_m * params_.robot_radius_m;
  for (int y = window_.y0; y < window_.y1; ++y) {
    for (int x = window_.x0; x < window_.x1; ++x) {
      if (grid_.at(x, y) != CellState::occupied || under_robot(x, y)) continue;
      for (const auto& step : kAxisSteps) {
        const int fx = x - step[0];
        const int fy = y - step[1];
        if (!window_.contains(fx, fy) || grid_.at(fx, fy) != CellState::free) continue;
        if (!part_of_object(x, y)) break;
        for (int k = 1; k <= depth; ++k) {
          const int sx = x + k * step[0];
          const int sy = y + k * step[1];
          if (!window_.contains(sx, sy) || grid_.at(sx, sy) != CellState::unknown) break;
          if ((grid_.center(sx, sy) - robot_).squaredNorm() <= radius2) break;
          std::uint8_t& mark = shadow_[index(sx, sy)];
          if (mark == 0) ++shadow_cells_;
          mark = 1;
        }
      }
    }
  }
}

// Measures the occupied cell's 8-connected component in the window once (its cells all take
// the answer): an object when its bounding box fits in a square of shadow_object_max_m.
bool NavigationMap::part_of_object(int x, int y) {
  const std::size_t seed = index(x, y);
  if (object_size_[seed] != kSizeUnmeasured) return object_size_[seed] == kSizeObject;
  const int max_cells = whole_cells(params_.explore.shadow_object_max_m, grid_.resolution_m);
  int x0 = x;
  int x1 = x;
  int y0 = y;
  int y1 = y;
  object_size_[seed] = kSizeMeasuring;
  const std::size_t tail = breadth_first(
      seed, kNeighbourSteps,
      [this](int nx, int ny, std::size_t) {
        if (!window_.contains(nx, ny) || grid_.at(nx, ny) != CellState::occupied) return false;
        std::uint8_t& size = object_size_[index(nx, ny)];
        if (size != kSizeUnmeasured) return false;
        size = kSizeMeasuring;
        return true;
      },
      [&](int cx, int cy) {
        x0 = std::min(x0, cx);
        x1 = std::max(x1, cx);
        y0 = std::min(y0, cy);
        y1 = std::max(y1, cy);
      });
  const bool object = x1 - x0 + 1 <= max_cells && y1 - y0 + 1 <= max_cells;
  for (std::size_t k = 0; k < tail; ++k) {
    object_size_[static_cast<std::size_t>(queue_[k])] = object ? kSizeObject : kSizeLarger;
  }
  return object;
}

bool NavigationMap::in_shadow(int x, int y) const { return window_.contains(x, y) && shadow_[index(x, y)] != 0; }

bool NavigationMap::in_pocket(int x, int y) const {
  return window_.contains(x, y) && region_label_[index(x, y)] == region_stamp_ + 1;
}

// The bounding box of the known cells and of the places where unknown cells may be crossed,
// grown by the ray cap so that every known cell sees its nearest unknown cell in the window.
void NavigationMap::find_window(const Eigen::Vector2d& robot, const Eigen::Vector2d& extra) {
  int x0 = grid_.width;
  int y0 = grid_.height;
  int x1 = -1;
  int y1 = -1;
  for (int y = 0; y < grid_.height; ++y) {
    const std::uint8_t* row = grid_.cells + grid_.index(0, y);
    const int first = first_known(row, grid_.width);
    if (first < 0) continue;
    const int last = last_known(row, grid_.width);
    x0 = std::min(x0, first);
    x1 = std::max(x1, last);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  const int travel = cells_for(params_.explore.unknown_travel_radius_m, grid_.resolution_m);
  const Eigen::Vector2d first = params_.explore.unknown_travel_near_robot ? robot : extra;
  for (const Eigen::Vector2d& centre : {first, extra}) {
    const Eigen::Vector2i cell = grid_.cell_of(centre);
    x0 = std::min(x0, cell.x() - travel);
    x1 = std::max(x1, cell.x() + travel);
    y0 = std::min(y0, cell.y() - travel);
    y1 = std::max(y1, cell.y() + travel);
  }
  const int grow = cells_for(std::max(params_.ray_cap_m(), params_.explore.preferred_clearance_m), grid_.resolution_m);
  window_.x0 = std::max(0, x0 - grow);
  window_.y0 = std::max(0, y0 - grow);
  window_.x1 = std::min(grid_.width, x1 + grow + 1);
  window_.y1 = std::min(grid_.height, y1 + grow + 1);
  if (window_.x1 < window_.x0) window_.x1 = window_.x0;
  if (window_.y1 < window_.y0) window_.y1 = window_.y0;
}

double NavigationMap::site_distance_m(const std::int32_t* sites, int x, int y) const {
  if (!window_.contains(x, y)) return kNoSiteDistance_m;
  const std::int32_t site = sites[index(x, y)];
  if (site == kNoSite) return kNoSiteDistance_m;
  const int dx = site_x(site) - x;
  const int dy = site_y(site) - y;
  return grid_.resolution_m * std::sqrt(static_cast<double>(dx * dx + dy * dy));
}

// Two-pass nearest-site propagation (8SSEDT): each cell takes the nearest site of the
// neighbours already visited (in a fixed order, the first of equals kept); exact up to rare
// sub-cell ties, which is all a 10 cm grid needs. Row by row with the window's edges
// handled outside the inner loops, each candidate's distance computed once.
template <typename IsSite>
void NavigationMap::distance_transform(std::int32_t* sites, IsSite&& is_site) {
  for (int y = window_.y0; y < window_.y1; ++y) {
    for (int x = window_.x0; x < window_.x1; ++x) {
      sites[index(x, y)] = is_site(x, y) ? pack_site(x, y) : kNoSite;
    }
  }
  const int x0 = window_.x0;
  const int x1 = window_.x1;
  // The nearest site so far of cell (x, y) is `best`, at squared distance `best2`.
  struct Nearest {
    int x, y;
    std::int32_t best;
    std::int64_t best2;
    void consider(std::int32_t candidate) {
      const std::int64_t candidate2 = site_distance2(candidate, x, y);
      if (candidate2 < best2) {
        best = candidate;
        best2 = candidate2;
      }
    }
  };
  auto start = [](std::int32_t own, int x, int y) { return Nearest{x, y, own, site_distance2(own, x, y)}; };
  // Forward: from the left, then the row above (left, straight, right); then from the right.
  for (int y = window_.y0; y < window_.y1; ++y) {
    std::int32_t* row = sites + index(0, y);
    const std::int32_t* above = y > window_.y0 ? sites + index(0, y - 1) : nullptr;
    for (int x = x0; x < x1; ++x) {
      Nearest nearest = start(row[x], x, y);
      if (x > x0) nearest.consider(row[x - 1]);
      if (above != nullptr) {
        if (x > x0) nearest.consider(above[x - 1]);
        nearest.consider(above[x]);
        if (x + 1 < x1) nearest.consider(above[x + 1]);
      }
      row[x] = nearest.best;
    }
    for (int x = x1 - 2; x >= x0; --x) {
      Nearest nearest = start(row[x], x, y);
      nearest.consider(row[x + 1]);
      row[x] = nearest.best;
    }
  }
  // Backward: the mirror image.
  for (int y = window_.y1 - 1; y >= window_.y0; --y) {
    std::int32_t* row = sites + index(0, y);
    const std::int32_t* below = y + 1 < window_.y1 ? sites + index(0, y + 1) : nullptr;
    for (int x = x1 - 1; x >= x0; --x) {
      Nearest nearest = start(row[x], x, y);
      if (x + 1 < x1) nearest.consider(row[x + 1]);
      if (below != nullptr) {
        if (x + 1 < x1) nearest.consider(below[x + 1]);
        nearest.consider(below[x]);
        if (x > x0) nearest.consider(below[x - 1]);
      }
      row[x] = nearest.best;
    }
    for (int x = x0 + 1; x < x1; ++x) {
      Nearest nearest = start(row[x], x, y);
      nearest.consider(row[x - 1]);
      row[x] = nearest.best;
    }
  }
}

// Where paths may cross unknown cells: under the robot's own disc (it stands there), and
// where the camera's blind zone may have left them: near the start pose (the robot starts in a
// disc whose floor the camera cannot see) and, with unknown_travel_near_robot, near the robot
// (a look from a goal leaves the ring within a metre unseen). Never a cell that was in view:
// that is a surface the stereo could not measure, such as a blank wall.
// With the grid's looked-over marks, only where a ray passed over the cell: one beside the
// robot's way that no view ever swept may hold a low box's side.
bool NavigationMap::unknown_passable(int x, int y) const {
  const Eigen::Vector2d centre = grid_.center(x, y);
  const double from_robot2 = (centre - robot_).squaredNorm();
  if (from_robot2 <= params_.robot_radius_m * params_.robot_radius_m) return true;
  if (params_.explore.in_view_blocks_travel && grid_.was_in_view(x, y)) return false;
  const double travel2 = params_.explore.unknown_travel_radius_m * params_.explore.unknown_travel_radius_m;
  return (centre - extra_unknown_centre_).squaredNorm() <= travel2 ||
         (params_.explore.unknown_travel_near_robot && from_robot2 <= travel2 &&
          (!grid_.marks_looked_over() || grid_.was_looked_over(x, y)));
}

// Near the robot, an unknown cell no ray passed over (grid.looked_over_range_m).
bool NavigationMap::unswept_near_robot(int x, int y) const {
  if (!grid_.marks_looked_over() || !params_.explore.unknown_travel_near_robot || grid_.was_looked_over(x, y)) {
    return false;
  }
  const double travel = params_.explore.unknown_travel_radius_m;
  return (grid_.center(x, y) - robot_).squaredNorm() <= travel * travel && !unknown_passable(x, y);
}

// What the robot must keep its radius (and the margin) away from: occupied cells, except deep
// under it; the unknown cells in a seen obstacle's shadow; and with unknown_clearance the
// unknown cells it may not cross (a blank wall the camera never saw: without this, paths ran
// along the seen floor with the disc in the wall); and near the robot, with the grid's
// looked-over marks, the unknown cells no view swept.
bool NavigationMap::obstacle_site(int x, int y) const {
  const CellState state = grid_.at(x, y);
  if (state == CellState::occupied) return !under_robot(x, y);
  if (state != CellState::unknown) return false;
  return in_shadow(x, y) || (params_.explore.unknown_clearance && !unknown_passable(x, y)) || unswept_near_robot(x, y);
}

bool NavigationMap::nearest_obstacles_aside(const Eigen::Vector2d& centre, const Eigen::Vector2d& across, double reach_m,
                                            Eigen::Vector2d& left, Eigen::Vector2d& right) const {
  const Eigen::Vector2i low = grid_.cell_of(centre - Eigen::Vector2d(reach_m, reach_m));
  const Eigen::Vector2i high = grid_.cell_of(centre + Eigen::Vector2d(reach_m, reach_m));
  double left2 = reach_m * reach_m;
  double right2 = left2;
  bool has_left = false;
  bool has_right = false;
  // A cell centre on the line through `centre` lies ahead or behind, not aside.
  const double on_line_m = 1e-6;
  for (int y = std::max(low.y(), window_.y0); y <= std::min(high.y(), window_.y1 - 1); ++y) {
    for (int x = std::max(low.x(), window_.x0); x <= std::min(high.x(), window_.x1 - 1); ++x) {
      if (!obstacle_site(x, y)) continue;
      const Eigen::Vector2d site = grid_.center(x, y);
      const double side = across.dot(site - centre);
      const double distance2 = (site - centre).squaredNorm();
      if (side > on_line_m && distance2 < left2) {
        left = site;
        left2 = distance2;
        has_left = true;
      } else if (side < -on_line_m && distance2 < right2) {
        right = site;
        right2 = distance2;
        has_right = true;
      }
    }
  }
  return has_left && has_right;
}

Eigen::Vector2d NavigationMap::centred_in_gap(const Eigen::Vector2i& cell, const Eigen::Vector2d& along,
                                              double reach_m) const {
  const Eigen::Vector2d centre = grid_.center(cell.x(), cell.y());
  if (reach_m <= 0.0 || along.squaredNorm() == 0.0) return centre;
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  Eigen::Vector2d left;
  Eigen::Vector2d right;
  if (!nearest_obstacles_aside(centre, across, reach_m, left, right)) return centre;
  // The point centre + s across as far from `left` as from `right`: |c + s a - l|^2 =
  // |c + s a - r|^2 gives s = (|c - r|^2 - |c - l|^2) / (2 a.(r - l)), and a.(r - l) < 0.
  const double shift = ((centre - right).squaredNorm() - (centre - left).squaredNorm()) / (2.0 * across.dot(right - left));
  const double half_cell = 0.5 * grid_.resolution_m;
  return centre + std::clamp(shift, -half_cell, half_cell) * across;
}

void NavigationMap::classify() {
  const double lethal = params_.lethal_distance_m(grid_.resolution_m);
  const double safe = params_.safe_distance_m(grid_.resolution_m);
  const double preferred = std::max(params_.explore.preferred_clearance_m, lethal + 1e-6);
  for (int y = window_.y0; y < window_.y1; ++y) {
    for (int x = window_.x0; x < window_.x1; ++x) {
      const std::size_t i = index(x, y);
      const CellState state = grid_.at(x, y);
      const double clearance = occupied_distance_m(x, y);
      Traversability kind = Traversability::safe;
      if ((state == CellState::occupied && !under_robot(x, y)) || clearance < lethal ||
          (state == CellState::unknown && !unknown_passable(x, y))) {
        kind = Traversability::lethal;
      } else if (clearance < safe) {
        kind = Traversability::inflated;
      }
      traversability_[i] = static_cast<std::uint8_t>(kind);
      const double closeness = std::clamp((preferred - clearance) / (preferred - lethal), 0.0, 1.0);
      const double unknown_cost = state == CellState::unknown ? params_.explore.unknown_cell_cost : 0.0;
      const double remembered_cost = state != CellState::occupied && grid_.was_seen_standing(x, y)
                                         ? params_.explore.remembered_obstacle_cost
                                         : 0.0;
      penalty_[i] =
          static_cast<float>(1.0 + params_.explore.obstacle_cost_weight * closeness + unknown_cost + remembered_cost);
    }
  }
}

// The robot stands there, so nothing else can: an occupied cell deep under it is a trace of
// something that has gone (a person who walked into it), not an obstacle to plan around.
// "Deep": a cell centre more than a cell inside the disc. The cell of an obstacle the robot
// merely grazes lies farther out (its centre is within half a cell diagonal of the surface)
// and stays an obstacle, so the plan leads away from it.
bool NavigationMap::under_robot(int x, int y) const {
  const double depth = std::max(0.0, params_.robot_radius_m - grid_.resolution_m);
  return (grid_.center(x, y) - robot_).squaredNorm() < depth * depth;
}

double NavigationMap::occupied_distance_m(int x, int y) const { return site_distance_m(occupied_site_.get(), x, y); }
double NavigationMap::unknown_distance_m(int x, int y) const { return site_distance_m(unknown_site_.get(), x, y); }

Traversability NavigationMap::traversability(int x, int y) const {
  if (!window_.contains(x, y)) return Traversability::lethal;
  return static_cast<Traversability>(traversability_[index(x, y)]);
}

bool NavigationMap::passable(int x, int y) const { return traversability(x, y) != Traversability::lethal; }

bool NavigationMap::nearest_passable(const Eigen::Vector2i& cell, double radius_m, Eigen::Vector2i& found) const {
  const int reach = static_cast<int>(std::floor(radius_m / grid_.resolution_m));
  const int reach_squared = reach * reach;
  int best = reach_squared + 1;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const int distance_squared = dx * dx + dy * dy;
      const int x = cell.x() + dx;
      const int y = cell.y() + dy;
      if (distance_squared >= best || !window_.contains(x, y) || !passable(x, y) || !in_sight(cell, {x, y})) continue;
      best = distance_squared;
      found = {x, y};
    }
  }
  return best <= reach_squared;
}

// The start cell is not checked: a goal's own cell may hold the trace that moved it.
bool NavigationMap::in_sight(const Eigen::Vector2i& a, const Eigen::Vector2i& b) const {
  return no_occupied_between(grid_, a, b, true);
}

double NavigationMap::step_cost(int from_x, int from_y, int to_x, int to_y) const {
  const bool diagonal = from_x != to_x && from_y != to_y;
  const double length = grid_.resolution_m * (diagonal ? kDiagonal : 1.0);
  return length * static_cast<double>(penalty_[index(to_x, to_y)]);
}

void NavigationMap::compute_reachable(const Eigen::Vector2i& start) {
  ++reach_stamp_;
  if (!window_.contains(start.x(), start.y())) return;
  const std::size_t start_index = index(start.x(), start.y());
  reached_stamp_[start_index] = reach_stamp_;
  reach_steps_[start_index] = 0;
  breadth_first(
      start_index, kNeighbourSteps,
      [this](int nx, int ny, std::size_t from) {
        if (!passable(nx, ny)) return false;
        const std::size_t next = index(nx, ny);
        if (reached_stamp_[next] == reach_stamp_) return false;
        reached_stamp_[next] = reach_stamp_;
        reach_steps_[next] = reach_steps_[from] + 1;
        return true;
      },
      [](int, int) {});
}

bool NavigationMap::reachable(int x, int y) const {
  return window_.contains(x, y) && reached_stamp_[index(x, y)] == reach_stamp_;
}

double NavigationMap::reach_distance_m(int x, int y) const {
  return reach_steps_[index(x, y)] * grid_.resolution_m;
}

}  // namespace stereoscout::explore
