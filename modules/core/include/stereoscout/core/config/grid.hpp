#pragma once
// Config section `grid`: the just-in-time maximum-likelihood occupancy grid (paper V).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

// The largest grid side the config takes (the navigation map packs a cell's coordinates into
// one word on that promise).
constexpr int kMaxGridSideCells = 20000;

struct GridConfig {
  int width_cells = 700;
  int height_cells = 700;
  double resolution_m = 0.10;
  double final_map_resolution_m = 0.01;
  double log_odds_hit = 0.85;
  double log_odds_miss = -0.4;
  double log_odds_min = -4.0;
  double log_odds_max = 4.0;
  double occupied_threshold = 0.65;
  double free_threshold = 0.196;
  double in_view_range_m = 0.0;
  double looked_over_range_m = 0.0;
  double free_end_sigmas = 0.0;
  double free_end_short_m = 0.0;
  double hit_full_weight_range_m = 0.0;
  double near_hit_hold_range_m = 0.0;
  double near_hit_hold_end_m = 1.5;
  bool once_per_scan = false;
  int cache_capacity = 64;
  int scan_history = 4096;
  double final_map_margin_m = 0.5;
  double final_map_tile_m = 4.0;
  int final_map_archive_tiles = 64;
};

inline void describe(ConfigVisitor& v, GridConfig& c) {
  v.begin_section("grid", "Occupancy grid of the maximum-likelihood particle, kept just in time (paper V).");
  v.integer_field("width_cells", c.width_cells, {10, kMaxGridSideCells, "cells", "Grid width (paper 700)."});
  v.integer_field("height_cells", c.height_cells, {10, kMaxGridSideCells, "cells", "Grid height (paper 700)."});
  v.number("resolution_m", c.resolution_m, {0.005, 1.0, "m", "Cell size of the navigation grid (paper 0.10). config/grid-5cm.yaml sets 0.05 with width_cells and height_cells 1400, explore.lethal_margin_cells 1 and explore.candidate_stride_cells 6 (the same extent, metric margin and goal lattice): over the office windows and the clutter hall it made 1 static contact against 8, and over the lab's three seeds to 1800 s and five office hours 1 static contact against 7 (the pose 0.14 m off), but the office at 93.7% on the mean against 97.5% (seed 5 78.8%: goals beside walls the grid left unknown), the lab later to 95% and the filter's ATE higher. Its replanning costs about 4 times the 0.1 grid's (host: 7 ms against 1.7 ms median). config/grid-5cm-near.yaml adds grid.hit_full_weight_range_m 3 and vision.dense_num_disparities 96: over the lab, the clutter hall and the office (twelve runs) 10 past 95% with 6 contacts, against the default's 10 with 9, but the corridor's blank wall driven into twice and the replanning past the host's budget. The default stays the paper's (docs/results.md)."});
  v.number("final_map_resolution_m", c.final_map_resolution_m, {0.005, 1.0, "m", "Cell size of the map written at the end of a run (paper 0.01)."});
  v.number("log_odds_hit", c.log_odds_hit, {0.0, 10.0, "", "Log-odds added to the cell where a ray ends on an obstacle."});
  v.number("log_odds_miss", c.log_odds_miss, {-10.0, 0.0, "", "Log-odds added to each cell a ray passes through."});
  v.number("log_odds_min", c.log_odds_min, {-100.0, 0.0, "", "Lower clamp of a cell's log-odds."});
  v.number("log_odds_max", c.log_odds_max, {0.0, 100.0, "", "Upper clamp of a cell's log-odds."});
  v.number("occupied_threshold", c.occupied_threshold, {0.0, 1.0, "", "Probability above which a cell is occupied (map.yaml occupied_thresh)."});
  v.number("free_threshold", c.free_threshold, {0.0, 1.0, "", "Probability below which a cell is free (map.yaml free_thresh)."});
  v.number("in_view_range_m", c.in_view_range_m, {0.0, 100.0, "m", "A cell that a scan column passes from where its floor becomes visible up to this range (to its obstacle, if nearer) was in view. An unknown cell in view is a surface the stereo could not measure (a blank wall), not the camera's blind zone: the planner never crosses it (explore.in_view_blocks_travel), and with explore.in_view_ends_goal_rays it lends a goal no value. Within 2 m the simulator's floor texture is measured (beyond, it fades). 0 (the default) marks nothing: with 2 m the office explored no more than with no unknown travel near the robot at all (44% against 70.5%; docs/results.md)."});
  v.number("looked_over_range_m", c.looked_over_range_m, {0.0, 100.0, "m", "Each scan column marks the cells its ray passes from the camera up to this range (to its end, if nearer) as looked over, the camera's blind zone included. With it, an unknown cell within explore.unknown_travel_radius_m of the robot is passable only if looked over (anything standing at the camera's height there would have been seen), and the unknown cells near the robot that no view ever swept (beside its way, out of the field of view: a low box's side the robot drove along) are kept clear of like occupied cells. 0 (the default) marks nothing, and every unknown cell near the robot is passable: at 3 m the clutter hall's three seeds made no contact in 900 s (the default one, a low box), at 96.9, 94.9 and 97.8% against 98.3, 94.9 and 98.0%, and lab seed 1 ran as the default, but the six office seeds reached 94.3% on the mean in 3600 s against 97.8% (95% on three seeds against five), with 8 contacts against 8 (docs/results.md). Not in the paper."});
  v.number("free_end_sigmas", c.free_end_sigmas, {0.0, 10.0, "sigma", "Within this many standard deviations of a free column's end range (range * vision.sigma_d_px / disparity) its misses lower no cell that holds an obstacle (log-odds above 0): the column's farthest floor point is the one the disparity error put farthest out, beyond the wall behind it, and floor seen up to a wall from both sides erased the wall. Unknown and free cells there are cleared as before. 0 (the default): every miss alike; at 2 the office's coverage fell from 49.3% to 39.9% over three seeds, as smeared door jambs and a walker's trace were kept too (docs/results.md); not in the paper."});
  v.number("free_end_short_m", c.free_end_short_m, {0.0, 1.0, "m", "A free column (floor seen up to its end) clears the floor up to this far short of its end point, or a cell short if that is more: the farthest floor point is the one the disparity error put farthest out, often beyond the wall behind it (0.11 m at 3 m for the paper's 0.5 px). 0 (the default): a cell short, 0.1 m on the default grid; a finer grid stops as short in metres only with this set. With the 5 cm grid, 0.1 left less free area outside the office's outer walls (0.04-1.48 m2 against 0.52-4.33 m2 over five seeds), but the office's coverage went from 7.6 points less to 11.5 more by seed (94.5% on the mean against 93.7%), with three jamb contacts against one (the estimate 0.13-0.42 m off), and the lab reached 95% later on two seeds of three (docs/results.md), so config/grid-5cm.yaml leaves it at 0. Not in the paper."});
  v.number("hit_full_weight_range_m", c.hit_full_weight_range_m, {0.0, 100.0, "m", "An obstacle column ending farther than this from the camera adds log_odds_hit x (this / range)^2 to its cell, not log_odds_hit: stereo's range error grows with the square of the range (0.23 m at 4.3 m for the paper's 0.5 px with the default camera, 4.6 cells of 5 cm), yet log_odds_hit alone (0.85, above the occupied threshold's 0.62) makes a cell occupied, a far hit as surely as a near one; a far wall seen at a slant may land its hits along the wall, in a door beside it. Nearer ends count in full. 0 (the default): every end in full. With config/grid-5cm.yaml at 3 m the office's six seeds reached 97.6% on the mean in 3600 s (the 5 cm grid alone 93.7% on five of them, the default 97.8%), with 4 static contacts against the default's 7, but two of them the corridor's blank wall, driven into from a south office, which the 5 cm grid alone never did in its five hours (docs/results.md). Not in the paper."});
  v.number("near_hit_hold_range_m", c.near_hit_hold_range_m, {0.0, 100.0, "m", "A low obstacle's hit (its point below the camera's height: a blank wall seen by its base, a box) from within this range of the camera holds its cell, unless misses from within this range once left the cell free (log-odds below free_threshold's), against the misses of columns that pass it farther than this from their camera, until a miss from nearer, or a hit at the camera's height, lowers it to log-odds 0 or below. Far misses still clear unknown and free cells, cells whose hits were all far (a far view's phantom) or at the camera's height (a person), and cells near views saw free (a door's jamb drawn into its doorway by a pose a little off: held, it shut a room whose door the robot then stood too far from to see clear); far misses that leave a cell free do not count, being how a blank wall is worn away. A ray's error across its way grows with its range (a degree of heading is 0.05 m at 3 m, half a cell), and the rays along a corridor reach its blank walls at a slant and from afar: a lineage a little off wore the office's corridor walls and partitions away in gaps that plans then ran through (docs/results.md). 0 (the default): every miss alike. At 2.5 m, fresh office seeds 7 and 8 reached 99.8% and 99.2% in 3600 s against the default's 87.2% and 86.0%, with no static contact against one each, but seed 1 87.9% against 92.8%, and seed 2 shut itself in a room at 955 s (44.3% against 96.8%): a copy of a wall drawn from near under a pose a little off is held like the wall, and no view from inside the room can lower it (docs/results.md). Not in the paper."});
  v.number("near_hit_hold_end_m", c.near_hit_hold_end_m, {0.0, 100.0, "m", "With near_hit_hold_range_m: a far miss passes a held cell by only where the cell lies within this distance of the miss's ray's end. The rays that wear a blank wall away end on it, at a slant, their error across their way moving their last cells onto the wall's; a ray that runs on farther beyond the cell saw through it (a doorway seen from inside its room, the corridor beyond it), and lowers it as any miss. 1.5 m: less than the office corridor's 2.2 m width, which a ray through a door from inside its room runs on across. Not in the paper."});
  v.boolean("once_per_scan", c.once_per_scan, "A scan lowers a cell that holds a low obstacle (log-odds above 0, its last hit not at the camera's height: a blank wall seen by its base, a low box) by log_odds_miss once, however many of its columns pass through it. Unknown and free cells, and obstacles at the camera's height (a person), take every column's miss, and every column ending in a cell adds its hit, as without it. Off: a cell counts a scan as many times as columns pass it, tens of times for a wall along which the rays graze, and a particle lineage whose pose is 0.1 m and a degree off erases a corridor wall in metre-long gaps that plans run through. On, it also keeps a door's smeared jambs and a drifting pose's second copy of a wall: office seed 2 ended shut in a room at 38.3% (default 86.2%), seed 6 at 79.7% (99.8%; docs/results.md). With config/grid-5cm.yaml and hit_full_weight_range_m 3 it made 2 static contacts in the six office hours against 4 without it, and none at a wall, but office seed 6 concluded \"explored\" at 456 s with 30.8%, a jamb copy 0.15 m inside N1's door leaving it 0.65 m between occupied cell centres (docs/results.md); not in the paper.");
  v.integer_field("cache_capacity", c.cache_capacity, {2, 100000, "grids", "Grids the just-in-time cache can hold, all allocated at start-up (width x height x 4 bytes each; paper saw 23 at most for 1000 particles). When full, the grid with the fewest dependents is evicted and counted."});
  v.integer_field("scan_history", c.scan_history, {1, 1000000, "scans", "Depth scans kept for roll-ups and the final map (the paper's run had 2209 updates; 16 bytes a column, 42 MB at 640 columns). Also bounds the walk to a grid-holding ancestor; a roll-up that needs an older scan skips it and counts rollup_incomplete. A scan that leaves the ring goes into the final map's archive (final_map_archive_tiles)."});
  v.number("final_map_margin_m", c.final_map_margin_m, {0.0, 100.0, "m", "Border added around the trajectory and its scans when the final map is sized."});
  v.number("final_map_tile_m", c.final_map_tile_m, {0.1, 100.0, "m", "Side of a tile of the final map's archive (at final_map_resolution_m: 4 m at 1 cm is 0.8 MB)."});
  v.integer_field("final_map_archive_tiles", c.final_map_archive_tiles, {0, 100000, "tiles", "Tiles allocated at start-up for the scans that leave the scan_history ring, so that the final map of a run longer than the ring still holds the whole trajectory (64 tiles of 4 m: 1024 square metres, 51 MB). A scan that needs a tile when none is left loses that part (pools.final_map_tiles.exhausted); 0 keeps none: the final map then lacks the scans that left the ring."});
  v.require(c.free_threshold < c.occupied_threshold, "free_threshold", "must be below occupied_threshold");
  v.end_section();
}

}  // namespace stereoscout::core
