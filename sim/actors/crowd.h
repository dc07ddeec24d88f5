#pragma once
// Crowds: groups of walkers that move between goals in an area with simple
// collision avoidance, simulated once when the world is built (a fixed step,
// seeded: the same scenario and seed give the same crowd).
//
// Each walker heads for its goal at its own speed, pushed away from walkers
// nearer than a few body widths and from static geometry (a social force),
// its heading turning toward its velocity. After each step a constraint pass
// keeps every two walkers' centres kCrowdSpacing apart and every walker
// kCrowdClearance from static geometry, so no two bodies and no body and rack
// ever overlap. A walker at its goal draws the next: the other end of the
// area ("ends", a busy aisle) or anywhere in it ("anywhere").
#include <cstdint>
#include <vector>

#include "sim/actors/actor_variation.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

constexpr double kCrowdSpacing = 0.7;     // m between two walkers' centres, at least
constexpr double kCrowdClearance = 0.35;  // m from a walker's centre to static geometry
constexpr double kCrowdStep = 0.04;       // s

// The walkers of every crowd (each `count` x `load`, rounded), as actors of
// action "crowd" with their tracks from t = 0 to `duration` s. Throws
// depot::Error naming the crowd's entry when its area cannot hold its walkers
// apart and clear of static geometry.
std::vector<ActorSpec> simulate_crowds(const std::vector<CrowdSpec>& crowds, double load,
                                       double duration, uint64_t world_seed,
                                       const ColumnClearance& clearance);

// A track's pose at time t (held before its first and after its last sample).
TrackPoint track_at(const std::vector<TrackPoint>& track, double t);

}  // namespace depot::sim
