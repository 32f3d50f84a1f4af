// stereoscout eval-disparity: runs the vision module's dense block matcher on a rectified
// pair from disk (Middlebury, KITTI) and prints JSON with the error rates against ground
// truth, the density and the time.
#include <chrono>
#include <cstdio>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "arguments.hpp"
#include "commands.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::cli {
namespace {

bool read_grey(const std::string& path, const char* what, cv::Mat& image) {
  image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    std::fprintf(stderr, "stereoscout eval-disparity: cannot read the %s image %s\n", what, path.c_str());
    return false;
  }
  return true;
}

}  // namespace

int run_eval_disparity(int argc, char** argv) {
  Arguments arguments("eval-disparity",
                      "Dense disparity of a rectified pair (left image is the reference) with the\n"
                      "census block matcher of the vision module; prints JSON. With --gt, scores\n"
                      "against ground truth (Middlebury: 0 = unknown, disparity = value / scale).");
  arguments.option("left", "PNG", "left image");
  arguments.option("right", "PNG", "right image");
  arguments.option("gt", "IMAGE", "ground-truth disparity of the left image (8 or 16 bit)");
  arguments.option("ndisp", "N", "disparities searched, 0 .. N-1", "64");
  arguments.option("scale", "S", "ground-truth value per pixel of disparity", "1");
  arguments.option("window", "PX", "aggregation window (odd)", "7");
  arguments.option("repeat", "N", "runs to time (the fastest is reported)", "3");
  // The other checks default to the config defaults (vision.dense_*), overridable to compare.
  const core::VisionConfig defaults{};
  arguments.option("uniqueness", "R", "uniqueness ratio", std::to_string(defaults.dense_uniqueness_ratio));
  arguments.option("texture", "G", "minimum texture, grey levels", std::to_string(defaults.dense_min_texture));
  arguments.option("speckle-region", "PX", "largest speckle region removed (0: off)",
                   std::to_string(defaults.dense_speckle_max_region_px));
  arguments.option("speckle-step", "PX", "disparity step inside one speckle region",
                   std::to_string(defaults.dense_speckle_max_step_px));
  arguments.option("baseline", "M",
                   "stereo baseline in metres, for the speckle filter's area rule (vision.dense_speckle_min_area_m2); "
                   "0: no area rule, as for pairs without a metric baseline",
                   "0");
  if (!arguments.parse(argc, argv)) {
    return arguments.exit_code();
  }
  long long disparities = 0;
  long long window = 0;
  long long repeat = 0;
  double scale = 1.0;
  long long speckle_region = 0;
  double baseline_m = 0.0;
  if (!arguments.get_double("baseline", baseline_m)) return 2;
  vision::DenseDisparityParams params = vision::dense_params_from_config(defaults, baseline_m);
  if (!arguments.get_int("ndisp", disparities) || !arguments.get_int("window", window) ||
      !arguments.get_int("repeat", repeat) || !arguments.get_double("scale", scale) ||
      !arguments.get_double("uniqueness", params.uniqueness_ratio) ||
      !arguments.get_double("texture", params.min_texture) || !arguments.get_int("speckle-region", speckle_region) ||
      !arguments.get_double("speckle-step", params.speckle_max_step_px)) {
    return 2;
  }
  if (!arguments.has("left") || !arguments.has("right") || disparities < 2 || window < 1 || window % 2 == 0 ||
      repeat < 1 || scale <= 0.0 || speckle_region < 0 || params.speckle_max_step_px < 0.0 || !(baseline_m >= 0.0)) {
    std::fprintf(stderr,
                 "stereoscout eval-disparity: need --left and --right, --ndisp >= 2, odd --window, --scale > 0,\n"
                 "--speckle-region >= 0, --speckle-step >= 0, --baseline >= 0\n");
    return 2;
  }
  cv::Mat left;
  cv::Mat right;
  if (!read_grey(arguments.get("left"), "left", left) || !read_grey(arguments.get("right"), "right", right)) {
    return 1;
  }
  if (left.size() != right.size()) {
    std::fprintf(stderr, "stereoscout eval-disparity: left and right images differ in size\n");
    return 1;
  }
  params.speckle_max_region_px = static_cast<int>(speckle_region);
  params.num_disparities = static_cast<int>(disparities);
  params.window_px = static_cast<int>(window);
  vision::DenseDisparityMatcher matcher(params, left.cols, left.rows);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  double best_ms = 0.0;
  for (long long run = 0; run < repeat; ++run) {
    const auto start = std::chrono::steady_clock::now();
    matcher.compute(left, right, disparity);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    best_ms = run == 0 ? ms : std::min(best_ms, ms);
  }
  const vision::DenseDisparityStats& stats = matcher.stats();
  std::printf("{\n  \"width\": %d, \"height\": %d, \"ndisp\": %lld, \"window\": %lld,\n", left.cols, left.rows,
              disparities, window);
  std::printf("  \"density_all_pixels\": %.4f, \"time_ms\": %.2f,\n",
              static_cast<double>(stats.valid) / static_cast<double>(stats.pixels), best_ms);
  std::printf("  \"rejected\": {\"texture\": %zu, \"uniqueness\": %zu, \"left_right\": %zu, \"speckle\": %zu, \"border\": %zu}",
              stats.rejected_texture, stats.rejected_uniqueness, stats.rejected_left_right, stats.rejected_speckle,
              stats.border);
  if (arguments.has("gt")) {
    const cv::Mat truth = cv::imread(arguments.get("gt"), cv::IMREAD_UNCHANGED);
    if (truth.empty() || truth.size() != left.size() || (truth.type() != CV_8UC1 && truth.type() != CV_16UC1)) {
      std::fprintf(stderr, "\nstereoscout eval-disparity: cannot use ground truth %s (missing, other size, or not 8/16-bit grey)\n",
                   arguments.get("gt").c_str());
      return 1;
    }
    const vision::DisparityScore score = vision::score_disparity(disparity, truth, scale);
    std::printf(",\n  \"known_pixels\": %zu, \"bad_1_0\": %.4f, \"bad_2_0\": %.4f, \"density\": %.4f, \"bad_2_0_all\": %.4f",
                score.known, score.bad_1, score.bad_2, score.density, score.bad_2_all);
  }
  std::printf("\n}\n");
  return 0;
}

}  // namespace stereoscout::cli
