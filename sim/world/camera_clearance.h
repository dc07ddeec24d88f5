#pragma once
// The camera's clearance to the static scene along a whole trajectory,
// checked before anything is rendered: a robot's or a person's camera never
// comes closer to furniture or walls than its body allows, and a camera
// closer than the sensor's minimum range sees a wall of texture without depth.
//
// Scenario keys (under `motion`): `clearance` (m; default the sensor's
// min_depth, 0.4 m) and `allow_close: true` (render anyway, with a warning).
#include <string>
#include <utility>
#include <vector>

#include "sim/camera/camera_motion.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/obstacles.h"

namespace depot::sim {

// Consecutive frames closer than the clearance, and the closest of them.
struct TooCloseRange {
  int first = 0, last = 0;
  int nearest_frame = 0;
  Nearest nearest;
};

struct CameraClearance {
  double required = 0.4;  // m
  int frame = -1;         // frame of the least clearance
  Nearest nearest;        // the least clearance over all frames
  std::vector<TooCloseRange> too_close;
};

// motion.clearance, or the sensor's min_depth when the file does not say.
double required_clearance(const Scenario& scenario);

// The camera centre's distance to static geometry at every frame timestamp.
CameraClearance measure_camera_clearance(
    const Scenario& scenario, const StaticObstacles& obstacles, const CameraMotion& motion,
    const std::vector<std::pair<double, double>>& frame_stamps);

// "frames 716-735 (0.05 m from 'crates_e' (crate) at frame 725), ..."
std::string describe_too_close(const CameraClearance& clearance);

// Nothing when the path keeps its clearance. Otherwise throws depot::Error
// naming the scenario file, the frames and the nearest objects, or, with
// motion.allow_close, prints one warning line with the frames to stderr.
void enforce_camera_clearance(const Scenario& scenario, const CameraClearance& clearance);

}  // namespace depot::sim
