#pragma once
// Config section `explore`: frontier-value goal selection, planning, driving (paper VI).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct ExploreConfig {
  double ray_step_deg = 5.0;
  double preferred_distance_m = 2.0;
  double distance_sigma_m = 0.5;
  double ray_cap_sigmas = 3.0;
  int candidate_stride_cells = 3;
  double safety_margin_m = 0.10;
  double lethal_margin_cells = 0.5;
  double min_goal_value = 3.0;
  double goal_distance_cost = 0.0;
  double max_pocket_area_m2 = 3.0;
  double goal_tolerance_m = 0.25;
  double goal_shift_radius_m = 0.0;
  int goal_failures_before_blacklist = 3;
  double visited_goal_radius_m = 0.5;
  double blacklist_radius_m = 2.0;
  int goal_memory = 512;
  double unknown_travel_radius_m = 1.0;
  bool unknown_travel_near_robot = true;
  bool unknown_clearance = false;
  double unknown_cell_cost = 1.0;
  double preferred_clearance_m = 0.8;
  double obstacle_cost_weight = 4.0;
  int max_plan_waypoints = 8192;
  double gap_centring_reach_m = 0.55;
  double lookahead_m = 0.35;
  double turn_in_place_deg = 25.0;
  double narrow_lookahead_m = 0.15;
  double safety_check_distance_m = 0.5;
  int scan_guard_min_points = 8;
  double scan_guard_max_age_s = 2.0;
  double scan_guard_distance_m = 0.8;
  double fresh_obstacle_margin_m = 0.0;
  double fresh_obstacle_hold_s = 3.0;
  double trace_forget_after_s = 10.0;
  double trace_confirm_radius_m = 2.0;
  int trace_view_updates = 5;
  double remembered_obstacle_cost = 0.0;
  bool wait_for_walkers = true;
  double walker_wait_per_goal_s = 20.0;
  double stuck_timeout_s = 40.0;
  double goal_time_factor = 3.0;
  double net_progress_timeout_s = 0.0;
  double failed_goal_cooldown_s = 0.0;
  double stall_window_s = 1.0;
  double stall_min_commanded_m = 0.04;
  double stall_progress_fraction = 0.25;
  double stall_back_off_m = 0.15;
  double contact_arc_deg = 25.0;
  int contact_memory = 256;
  double contact_hold_s = 600.0;
  double contact_repeat_radius_m = 0.2;
  double trail_length_m = 30.0;
  double trail_contact_radius_m = 0.0;
  int event_memory = 4096;
  double time_limit_s = 3600.0;
  bool pan_at_goal = true;
  bool return_to_start = true;
};

inline void describe(ConfigVisitor& v, ExploreConfig& c) {
  v.begin_section("explore", "Exploration: goal value H(s), A* planning and path following (paper VI).");
  v.number("ray_step_deg", c.ray_step_deg, {0.5, 90.0, "deg", "Angle between the rays cast from a candidate goal (paper 5)."});
  v.number("preferred_distance_m", c.preferred_distance_m, {0.1, 20.0, "m", "r*: distance to unknown space that maximises V (paper 2.0)."});
  v.number("distance_sigma_m", c.distance_sigma_m, {0.01, 10.0, "m", "sigma of V (paper 0.5)."});
  v.number("ray_cap_sigmas", c.ray_cap_sigmas, {0.5, 10.0, "sigma", "Rays stop at r* + this many sigma; a ray that meets no unknown cell by then adds 0 (the paper's V there is below exp(-4.5) at 3)."});
  v.integer_field("candidate_stride_cells", c.candidate_stride_cells, {1, 20, "cells", "H is evaluated on a lattice of this spacing, then at full resolution around the best lattice cell."});
  v.number("safety_margin_m", c.safety_margin_m, {0.0, 2.0, "m", "Added to the robot radius when inflating obstacles; goals keep this clearance, paths pay a high cost inside it."});
  v.number("lethal_margin_cells", c.lethal_margin_cells, {0.0, 1.0, "cells", "A cell whose centre is nearer than the robot radius plus this fraction of a cell to an occupied cell's centre is lethal: the obstacle's surface may lie anywhere in its cell. The robot (0.7 m) passes a 0.9 m door with a cell to spare at 0.5, the default; one smeared jamb cell closes it."});
  v.number("goal_distance_cost", c.goal_distance_cost, {0.0, 100.0, "per m", "Goal selection ranks H(s) minus this much per metre of path from the robot (the reachable fill's distance), so that a goal across the building must be worth that much more than one nearby. 0 (the default): the paper's argmax H, which crosses the office end to end for goals a few points above those beside the robot. At 0.5 office seeds 2 and 3 reached 50.8% and 91.0% in 3600 s against 84.4% and 86.8% (seed 2 never went east of its middle, taking one nearby goal worth 6-11 after another); at 0.15, 85.8% and 82.5% (docs/results.md). Not in the paper."});
  v.number("min_goal_value", c.min_goal_value, {0.0, 1000.0, "", "Exploration ends when no goal is worth more than this (about three rays seeing unknown space at r*; small unknown pockets, such as the floor under a table, are not worth a trip)."});
  v.number("max_pocket_area_m2", c.max_pocket_area_m2, {0.0, 1000.0, "m^2", "An unknown region enclosed by known cells and no larger than this (inside a low box or cupboard, under a table, along a wall) cannot be seen from the free space and is not a frontier; 0 treats every unknown region as a frontier."});
  v.number("goal_tolerance_m", c.goal_tolerance_m, {0.01, 5.0, "m", "A goal is reached within this distance."});
  v.number("goal_shift_radius_m", c.goal_shift_radius_m, {0.0, 5.0, "m", "When a later update makes the goal's cell impassable (a new obstacle cell nearby: a person's trace, a stereo outlier), plans go to the nearest passable cell within this distance of it in sight of it instead of failing the goal; its view is nearly the same. 0 = off, the default: with true poses it halves goal failures, but with the filter it lowered coverage in all six office and clutter runs measured at 0.5 m (docs/results.md); not in the paper."});
  v.integer_field("goal_failures_before_blacklist", c.goal_failures_before_blacklist, {1, 100, "", "A goal that failed this many times is never chosen again; the return to the start is given up at its this-many-th failure (no plan, or no progress for stuck_timeout_s), with a look and a new try after each before that."});
  v.number("visited_goal_radius_m", c.visited_goal_radius_m, {0.0, 10.0, "m", "Candidates this close to an already visited goal are skipped, and failures of goals this close to each other count as one goal's."});
  v.number("blacklist_radius_m", c.blacklist_radius_m, {0.0, 10.0, "m", "Candidates this close to a blacklisted goal are skipped (at least visited_goal_radius_m). A room seen through a door the robot cannot pass offers goal after goal beside the last one blacklisted, each failing after a drive there. The default, 2 m, is preferred_distance_m's: the goals within it look at the same unknown space."});
  v.integer_field("goal_memory", c.goal_memory, {1, 100000, "goals", "Failed and visited goals remembered (fixed list; when full, new ones are counted and forgotten)."});
  v.number("unknown_travel_radius_m", c.unknown_travel_radius_m, {0.0, 5.0, "m", "Paths may cross unknown cells this close to the start pose (the camera cannot see the floor right in front of it, so the robot starts in an unknown disc) and, with unknown_travel_near_robot, to the robot; never a cell that was in view."});
  v.boolean("unknown_travel_near_robot", c.unknown_travel_near_robot, "Paths may also cross unknown cells within unknown_travel_radius_m of the robot wherever it is (after a look from a goal, the ring within a metre is unseen), except cells that were in view (grid.in_view_range_m): those are surfaces the stereo could not measure, such as a blank wall.");
  v.boolean("unknown_clearance", c.unknown_clearance, "Unknown cells that paths may not cross are kept clear of like occupied cells (robot radius, safety margin, clearance cost): a blank wall stays unknown, and without this paths run along the floor seen up to it with the robot's disc in the wall. Off by default: with it, 1000-particle clutter reached 85.4% in 900 s and the office ended by itself at 16% (docs/results.md).");
  v.number("unknown_cell_cost", c.unknown_cell_cost, {0.0, 100.0, "", "Extra A* cost per metre through an unknown cell."});
  v.number("preferred_clearance_m", c.preferred_clearance_m, {0.0, 5.0, "m", "A* pays an obstacle penalty on cells closer than this to an occupied cell."});
  v.number("obstacle_cost_weight", c.obstacle_cost_weight, {0.0, 1000.0, "", "Extra A* cost per metre at the lethal distance, falling linearly to 0 at preferred_clearance_m."});
  v.integer_field("max_plan_waypoints", c.max_plan_waypoints, {2, 10000000, "cells", "Capacity of a plan; a longer path is a counted planning failure."});
  v.number("gap_centring_reach_m", c.gap_centring_reach_m, {0.0, 5.0, "m", "A plan runs through cell centres: through a 0.9 m door spanning an even number of cells, 0.05 m off its middle, where the robot (0.7 m) has 0.1 m to spare on either side. Each waypoint (but the first and last) with obstacle cells on both sides of the plan within this distance of its cell's centre is moved across the plan to the point as far from the nearest on one side as from the nearest on the other, by at most half a cell, so it stays in its passable cell. Nearest, not straight across: a thin wall's door has its jambs straight across only the waypoint in the wall, and the robot's disc passes the jambs from the waypoints before and after it. At the lethal distance plus 1.5 cells (0.55 m on the default robot) it reaches the jambs of doors up to 1.1 m wide. 0 = off. On by default since 2026-11-27 with narrow_lookahead_m (measured together, docs/results.md): with both, the office's door passages were 0.014-0.031 m off their middles on the median over four seeds, against 0.032-0.051 m, and 0.004 m with true poses. An earlier version that looked straight across only moved the waypoint in the wall alone and left the passages as they were. Not in the paper."});
  v.number("lookahead_m", c.lookahead_m, {0.05, 5.0, "m", "Pure-pursuit lookahead distance of the path follower."});
  v.number("narrow_lookahead_m", c.narrow_lookahead_m, {0.0, 5.0, "m", "The follower's lookahead while a waypoint up to the lookahead point lies within the safety margin of an obstacle (a doorway): pure pursuit cuts a corner by a fraction of its lookahead, and a 0.7 m robot in a 0.9 m door has 0.10 m to spare on either side. 0 = lookahead_m everywhere. With gap_centring_reach_m at 0.55, driving a kinematic robot through a door from 96 approaches (PathFollower.PassesADoorNearItsMiddle), the disc kept at least 0.095 m from the jambs at 0.15 (0.097 m at 0.1, 0.091 m at 0.2; 0.068 m with gap centring alone), against 0.039 m with both off. On office seeds 2-5 at 3600 s with both on: 4 door-jamb contacts against 7, coverage 93.7, 99.3, 98.5 and 73.7% against 84.4, 86.8, 97.4 and 97.5% (on seed 5 the filter's heading was 8-9 degrees off from 695 s on: it took the robot into a jamb at 700 s and its position 0.6 m off by 790 s). Not in the paper."});
  v.number("turn_in_place_deg", c.turn_in_place_deg, {1.0, 180.0, "deg", "The follower turns in place while the lookahead point is farther off the heading than this."});
  v.number("safety_check_distance_m", c.safety_check_distance_m, {0.05, 5.0, "m", "Before every command the next stretch of path this long is checked against occupied cells."});
  v.integer_field("scan_guard_min_points", c.scan_guard_min_points, {0, 100000, "columns", "The safety check also holds the robot still (no look: most likely a walker crossing) when at least this many columns of the latest scan saw an obstacle at the camera's height (a person, a textured wall) inside the robot's disc ahead, along the plan and along its heading (to the plan's end), within scan_guard_distance_m. The grid turns a cell it saw free many times occupied only after several updates, and a person walking towards the robot is there first. A person 1 m away fills a couple of hundred columns; a few stray matches do not stop the robot; 8 is the value measured. 0 = off. On by default since 2026-11-26, for safety: without it the robot drove into the office's walker coming head-on in view on both seeds measured, and with it it held for them. Measured then, coverage was alike in clutter and the lab (clutter seeds 1-3 at 900 s: 97.5, 98.3 and 95.3% against 90.1, 98.9 and 98.4%; lab seeds 1 and 3 at 1800 s: 99.1 and 99.7% against 98.9 and 99.7%) but fell in the office on both seeds (3600 s: 95.4 and 82.4% against 97.4 and 94.4%). A walker who comes from outside the view it cannot see (docs/results.md). Not in the paper."});
  v.number("scan_guard_distance_m", c.scan_guard_distance_m, {0.0, 5.0, "m", "How far ahead the scan_guard_min_points check looks, along the heading and along the plan. The dense matcher sees nothing nearer the camera than focal * baseline / dense_num_disparities (0.63 m on the default camera, 0.73 m from the robot's centre), and an update follows only every update_min_translation_m of travel, so the check must reach beyond that for a walker to be in view at one update at least."});
  v.number("scan_guard_max_age_s", c.scan_guard_max_age_s, {0.0, 100.0, "s", "The scan_guard_min_points check uses the latest scan only while it is younger than this. Updates follow motion, so a robot held still keeps its last scan: the hold ends when that is this old, and the next update, update_min_translation_m on, holds it again if the obstacle is still there. During a hold the robot does not turn either, and a later scan does not end it: a walker who came nearer than the matcher sees is in no later scan (since 2026-11-27; before, a turn in place 0.1 s into a hold brought an update without the walker on lab seed 1, and the robot drove into them)."});
  v.number("fresh_obstacle_margin_m", c.fresh_obstacle_margin_m, {0.0, 2.0, "m", "The safety check keeps this much more clearance from cells that turned from free to occupied within fresh_obstacle_hold_s (a person walking at 0.5 m/s moves 0.3 m between two updates). 0 = off, the default: measured at 0.3 m it did not reduce contacts with people (docs/results.md); not in the paper."});
  v.number("fresh_obstacle_hold_s", c.fresh_obstacle_hold_s, {0.0, 60.0, "s", "How long a cell that turned from free to occupied counts as fresh for fresh_obstacle_margin_m."});
  v.number("trace_forget_after_s", c.trace_forget_after_s, {0.0, 3600.0, "s", "A cell that turned from free to occupied this long ago is a trace (a person who walked on, seen from where the robot could not see it go). Before concluding that a goal has no plan or that nothing is left, the explorer lets plans cross traces until that goal is reached or fails; the safety check still stops for them, and a look confirms one as an obstacle if it is still there. A trace next to a standing obstacle is part of it and not crossed. 0 = off. On the office (four seeds) it raised coverage from 33.3% to 49.0% on the mean, with 11 contacts against 8; on clutter (three seeds) it lowered it from 90.2% to 88.4% (docs/results.md). Not in the paper."});
  v.number("trace_confirm_radius_m", c.trace_confirm_radius_m, {0.0, 20.0, "m", "After a look, traces within this distance that the grid still holds occupied are obstacles, no longer crossed by plans."});
  v.integer_field("trace_view_updates", c.trace_view_updates, {0, 1000, "updates", "A cell that turned from free to occupied and stays occupied through this many observation updates in the camera's view (within its field of view, between the nearest floor it sees and trace_confirm_radius_m, in sight on the grid) is a standing obstacle, never a trace: a gone person's cell in view is crossed by rays and cleared within a few updates, and a blank wall's restored cell is not. 0 = off (only looks confirm). On the office (four seeds) it raised coverage from 49.0% to 55.0% on the mean, on clutter (three) it gave 87.1% against 88.4%, and the lab's seed 2 ran byte for byte as before (docs/results.md). Not in the paper."});
  v.boolean("wait_for_walkers", c.wait_for_walkers, "A plan blocked only by cells that turned from free to occupied less than trace_forget_after_s ago and were not seen standing (trace_view_updates) is kept rather than replanned: a person crossing it will most likely have walked on when the robot gets there, and if not, the safety check stops the robot and it looks. Without this, a person walking to and fro across the robot's way sent it on one detour after another (clutter). Limited by walker_wait_per_goal_s. With that limit it raised clutter's coverage from 90.6% to 95.1% on the mean of three seeds (contacts 3 to 0) and the office's from 49.5% to 54.7% on the mean of four (contacts 7 to 9); the lab stayed at 99.3-99.6% on three seeds, with two contacts where it had none, neither of them on a kept plan. Without the limit the office lost 11.7 points (docs/results.md). Not in the paper.");
  v.number("walker_wait_per_goal_s", c.walker_wait_per_goal_s, {0.0, 100000.0, "s", "With wait_for_walkers, how long in all one goal's plans may be kept while blocked by passers-by; from then on a blocked plan is replanned as without it. A person crosses the robot's way in a few seconds (0.7 m of robot and 0.5 m of person at 0.3-0.8 m/s, plus the updates that clear the trace); a plan still blocked after that is blocked by something else, such as a blank wall whose cells grazing rays erased and the next view restored, which look the same. Without a limit the office's robot pursued single goals through its corridor walls for 200-420 s on kept plans. Not in the paper."});
  v.number("remembered_obstacle_cost", c.remembered_obstacle_cost, {0.0, 10000.0, "", "Extra A* cost per metre through a cell the explorer saw standing (trace_view_updates) that the grid now holds free or unknown: a blank wall's cells, erased by rays that graze it or by floor seen from its other side with another pose error, stay costly to cross, so plans take the door rather than the gap. A cost, not an obstacle, so a map that shifted with the pose estimate does not close doors. 0 = off, the default: at 200 it lowered the office's coverage on two seeds of two measured (36.8% against 46.8% on their mean; docs/results.md). Not in the paper."});
  v.number("stuck_timeout_s", c.stuck_timeout_s, {1.0, 100000.0, "s", "A goal fails when the robot got no closer to it along its plan (the plan's remaining length) for this long."});
  v.number("goal_time_factor", c.goal_time_factor, {0.0, 1000.0, "", "A goal (or the way back) also fails when pursued for longer than stuck_timeout_s plus this many times the driving time of its longest plan at robot.max_speed_mps. Progress is measured along the plan and a longer plan (a detour around a wall the map had held free) restarts it, so a robot alternating between two routes would otherwise never fail. 0: no limit. Not in the paper."});
  v.number("net_progress_timeout_s", c.net_progress_timeout_s, {0.0, 100000.0, "s", "A goal (or the way back) also fails when the robot has not come nearer to it than ever before, along whichever plan it has, for this long. stuck_timeout_s measures progress along the current plan and restarts with a longer one; a robot that goes back and forth between a short route through a gap the map holds in a blank wall and the long way round makes progress on each and comes no nearer. 0 = off, the default: at 150 s with failed_goal_cooldown_s at 300 s, office seeds 2 and 3 reached 93.8% and 79.8% in 3600 s against 84.4% and 86.8%; with trail_contact_radius_m at 0.25 as well, 93.7% and 83.2%, seed 1 96.8% against 95.4%, but seeds 4 and 5 89.1% and 85.5% against 97.4% and 97.5%: 89.7% on the mean of five seeds against 92.3% (docs/results.md). Not in the paper."});
  v.number("failed_goal_cooldown_s", c.failed_goal_cooldown_s, {0.0, 100000.0, "s", "Candidates within blacklist_radius_m of a goal that failed less than this long ago are not chosen, so that a goal that just failed is not taken up again at once, from where it failed, before the others are tried (it is still chosen again later, up to goal_failures_before_blacklist failures). 0 = off, the default; measured with net_progress_timeout_s (its entry). Not in the paper."});
  v.number("stall_window_s", c.stall_window_s, {0.1, 60.0, "s", "Stall detector: the commanded forward travel and the travel the pose shows (odometry between updates) are compared over windows at least this long."});
  v.number("stall_min_commanded_m", c.stall_min_commanded_m, {0.001, 10.0, "m", "Stall detector: a window is judged once at least this much forward travel was commanded in it; a slower command stretches the window (a tick without a forward command starts a new one)."});
  v.number("stall_progress_fraction", c.stall_progress_fraction, {0.0, 1.0, "", "Stall detector: the robot is stalled (pushing against something it did not see) when it moved less than this fraction of the commanded travel."});
  v.number("stall_back_off_m", c.stall_back_off_m, {0.0, 2.0, "m", "After a stall the robot backs off this far at its top speed (while the disc behind is clear in the grid, and for at most twice the time it needs) before it looks and replans: a plan from the point of contact leads into the same contact. 0 = off; not in the paper."});
  v.number("contact_arc_deg", c.contact_arc_deg, {0.0, 90.0, "deg", "A stall marks the cells just beyond the robot's rim straight ahead and this far to either side as occupied for planning."});
  v.integer_field("contact_memory", c.contact_memory, {1, 100000, "cells", "Contact cells remembered (fixed list; when full, new ones are counted and forgotten)."});
  v.number("contact_repeat_radius_m", c.contact_repeat_radius_m, {0.0, 5.0, "m", "Before concluding that nothing is left or that there is no way back, the explorer clears the contact cells (they can close a door whose jamb the robot touched); a contact made again within this distance of one it cleared is real and is not cleared again, only forgotten as any contact is. Without this, a plain pillar in a gap the grid held open was driven into 25 times in 430 s, the contact cleared each time the explorer found nothing else to do (clutter, seed 6, docs/results.md). 0 = clear every time. Not in the paper."});
  v.number("trail_length_m", c.trail_length_m, {0.0, 1000.0, "m", "The last this many metres of the robot's own path are remembered (a point every 5 cm). Before concluding that nothing is left or that there is no way back, plans may follow that path where the grid has closed it: its cells count as passable (at the highest obstacle cost) unless occupied or nearer an occupied cell than the robot's radius, where the safety check would stop the robot anyway. A passage the robot came in by can close behind it when a smeared cell narrows it below the lethal width (clutter, seed 6, docs/results.md). 0 = off. Not in the paper."});
  v.number("trail_contact_radius_m", c.trail_contact_radius_m, {0.0, 5.0, "m", "A contact point (contact_arc_deg) within this distance of the robot's trail (trail_length_m: where its centre was) is not recorded: the robot's disc passed there, so no surface stands there. A robot leaving a room by the door it came in by and touching a jamb pushes with the doorway ahead, and a contact cell there shut the door for contact_hold_s (office seed 2: 600 s in S2). Below the robot's radius by the pose error between the two passes; at the robot's radius plus half a cell or more it would drop every contact, since the trail's newest points lie that far behind the rim. 0 = off, the default: at 0.25 office seed 2 ran byte for byte as without it and seed 3 reached 81.6% against 86.8%, touching N1's door jamb twice where it touched it once; with the other two rules, see net_progress_timeout_s (docs/results.md). Not in the paper."});
  v.number("contact_hold_s", c.contact_hold_s, {1.0, 1e7, "s", "A contact cell is forgotten after this long, or earlier when the grid sees its cell free after holding it unknown or occupied (a person who walked on)."});
  v.integer_field("event_memory", c.event_memory, {1, 10000000, "events", "Explorer events kept for the run directory's explore_events.csv (goals chosen, reached and failed, replans, stops, stalls, looks; a fixed ring: when full the oldest is dropped and counted)."});
  v.number("time_limit_s", c.time_limit_s, {1.0, 1e7, "s", "Exploration ends after this long (then returns to start if configured)."});
  v.boolean("pan_at_goal", c.pan_at_goal, "Look around 360 degrees on reaching each goal (paper VI).");
  v.boolean("return_to_start", c.return_to_start, "Drive back to the start pose when exploration ends.");
  v.end_section();
}

}  // namespace stereoscout::core
