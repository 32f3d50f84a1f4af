#pragma once
// The wheel-odometry error model shared by every platform that makes odometry from a true
// motion (the simulator, datasets without wheel encoders): random errors are a random walk
// (variance proportional to the distance driven and the angle turned), systematic ones a
// scale error and a heading drift per metre. Parameters: config OdometryNoiseConfig.

#include "stereoscout/core/config/sim.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/random.hpp"

namespace stereoscout::core {

// The odometry's view of a true motion `delta` (robot frame), drawing two Gaussians.
Pose2 corrupt_motion(const Pose2& delta, const OdometryNoiseConfig& noise, RandomStream& random);

}  // namespace stereoscout::core
