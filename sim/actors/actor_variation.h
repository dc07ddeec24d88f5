#pragma once
// What the world seed varies in a scenario's actors, so that seeds sample
// actor motion and not only sensor noise. Each actor draws from its own
// stream, derive_seed(world seed, hash of its name, ...), so adding an actor
// or changing the dynamic load leaves the others' draws alone:
//
//  - walkers, animals and birds: where on their path they are at t = 0
//    (uniform over one lap), speed x [0.9, 1.1], the gait phase, and a smooth
//    sideways shift within their lane (at most kLaneHalfWidth, birds
//    kBirdLaneHalfWidth) that never takes the path closer to static geometry
//    than min(its written clearance, kActorClearance): otherwise the shift is
//    mirrored to the other side, then halved (twice), and else dropped;
//  - pushers and carriers: start time + [0, 1] s, speed x [0.92, 1.08], gait
//    phase; their path is kept (it must meet the chair or cart; the goods
//    rest at its ends); a carrier's waits come from its appearance;
//  - sitters, chairs and carts: their appearance only;
//  - everyone: appearance (clothes, fur and feather colours, size within a few
//    per cent, idle-motion phase, the goods on a cart) unless `appearance` is
//    written in the file.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/scenario/scenario.h"

namespace depot::sim {

constexpr double kLaneHalfWidth = 0.15;      // m, ground actors
constexpr double kBirdLaneHalfWidth = 0.25;  // m
constexpr double kActorClearance = 0.35;     // m, path centre to static geometry

// A stable 64-bit hash of an actor's name (FNV-1a; std::hash differs between
// standard libraries, and datasets must not).
uint64_t name_hash(const std::string& name);

// The horizontal distance (m, negative inside) from a body standing at `xy`
// over heights z_lo..z_hi to the nearest static geometry: the scene's
// (sim/scene/obstacles.h: StaticObstacles::column_clearance), which is built
// above the actors and so handed down.
using ColumnClearance = std::function<double(const Eigen::Vector2d& xy, double z_lo, double z_hi)>;

std::vector<ActorSpec> vary_actors(const std::vector<ActorSpec>& actors, uint64_t world_seed,
                                   const ColumnClearance& clearance);

// One point of an actor's path as written and as varied (the same point of
// the smoothed path, shifted), with their clearances to static geometry at
// the actor's body heights.
struct LaneSample {
  Eigen::Vector2d written, varied;
  double written_clearance = 0, varied_clearance = 0;
};
// Samples every few centimetres along the path of `varied` (a walker, animal
// or bird) and of the same actor as written (`written`).
std::vector<LaneSample> lane_samples(const ActorSpec& written, const ActorSpec& varied,
                                     const ColumnClearance& clearance);

// Whether an actor follows a path the world seed may shift (walk and fly).
bool has_lane(const ActorSpec& actor);
double lane_half_width(const ActorSpec& actor);

}  // namespace depot::sim
