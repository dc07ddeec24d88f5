#include "sim/actors/actor_variation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "common/rng.h"
#include "sim/actors/actor.h"

namespace depot::sim {
namespace {

// Independent streams of one actor.
constexpr uint64_t kAppearanceStream = 1;
constexpr uint64_t kTimingStream = 2;
constexpr uint64_t kLaneStream = 3;

constexpr double kSampleStep = 0.05;        // m between lane samples
constexpr double kMinLaneWavelength = 6.0;  // m: people and animals do not weave

// Heights of the actor's body above the floor (m).
std::pair<double, double> body_heights(const ActorSpec& a) {
  const Eigen::AlignedBox3d e = make_actor(a, nullptr)->local_extent();
  if (a.type == "bird") return {a.height - 0.08 + e.min().z(), a.height + 0.08 + e.max().z()};
  return {0.0, e.max().z()};
}

// factor < 0 mirrors the shift to the other side of the path.
LaneOffset scaled(LaneOffset o, double factor) {
  o.constant *= factor;
  o.amplitude *= factor;
  return o;
}

bool keeps_clear(const std::vector<LaneSample>& samples) {
  return std::all_of(samples.begin(), samples.end(), [](const LaneSample& s) {
    return s.varied_clearance >= std::min(s.written_clearance, kActorClearance) - 1e-9;
  });
}

}  // namespace

uint64_t name_hash(const std::string& name) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : name) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

bool has_lane(const ActorSpec& a) {
  return a.action == "walk" || a.action == "fly";
}

double lane_half_width(const ActorSpec& a) {
  return a.type == "bird" ? kBirdLaneHalfWidth : kLaneHalfWidth;
}

std::vector<LaneSample> lane_samples(const ActorSpec& written, const ActorSpec& varied,
                                     const ColumnClearance& clearance) {
  const Path2D as_written = actor_path(written), as_varied = actor_path(varied);
  const std::vector<Eigen::Vector2d>& p = as_written.points();
  const std::vector<Eigen::Vector2d>& q = as_varied.points();
  const auto [z_lo, z_hi] = body_heights(varied);
  std::vector<LaneSample> out;
  // The lane shift moves each point of the smoothed path sideways, so the
  // i-th points (and the points between them) correspond.
  for (size_t i = 0; i + 1 < p.size() && i + 1 < q.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil((p[i + 1] - p[i]).norm() / kSampleStep)));
    for (int k = 0; k < n; ++k) {
      const double u = static_cast<double>(k) / n;
      LaneSample s;
      s.written = p[i] + u * (p[i + 1] - p[i]);
      s.varied = q[i] + u * (q[i + 1] - q[i]);
      s.written_clearance = clearance(s.written, z_lo, z_hi);
      s.varied_clearance = clearance(s.varied, z_lo, z_hi);
      out.push_back(s);
    }
  }
  return out;
}

std::vector<ActorSpec> vary_actors(const std::vector<ActorSpec>& actors, uint64_t world_seed,
                                   const ColumnClearance& clearance) {
  std::vector<ActorSpec> out = actors;
  for (ActorSpec& a : out) {
    const uint64_t key = name_hash(a.name);
    if (!a.fixed_appearance) a.appearance = derive_seed(world_seed, key, kAppearanceStream);
    Rng timing(derive_seed(world_seed, key, kTimingStream));
    if (a.action == "push" || a.action == "carry") {
      a.start_time += timing.uniform(0.0, 1.0);
      a.speed *= timing.uniform(0.92, 1.08);
      a.gait_phase = timing.uniform(0.0, 2.0 * M_PI);
      continue;
    }
    if (!has_lane(a)) continue;
    const ActorSpec written = a;
    const double lap = actor_path(written).length();
    a.start_offset += timing.uniform(0.0, lap);
    a.speed *= timing.uniform(0.9, 1.1);
    a.gait_phase = timing.uniform(0.0, 2.0 * M_PI);

    Rng lane(derive_seed(world_seed, key, kLaneStream));
    const double r = lane_half_width(a);
    LaneOffset drawn;
    drawn.constant = lane.uniform(-0.5 * r, 0.5 * r);
    drawn.amplitude = lane.uniform(0.0, r - std::abs(drawn.constant));
    const int max_cycles = std::max(1, static_cast<int>(lap / kMinLaneWavelength));
    drawn.cycles = 1 + static_cast<int>(lane.below(static_cast<uint64_t>(max_cycles)));
    drawn.phase = lane.uniform(0.0, 2.0 * M_PI);
    // The drawn shift, mirrored, then smaller, until the path keeps clear.
    a.lane = LaneOffset();
    for (double factor : {1.0, -1.0, 0.5, -0.5, 0.25, -0.25}) {
      ActorSpec candidate = a;
      candidate.lane = scaled(drawn, factor);
      if (keeps_clear(lane_samples(written, candidate, clearance))) {
        a.lane = candidate.lane;
        break;
      }
    }
  }
  return out;
}

}  // namespace depot::sim
