#include "slam/io/map_file.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/image_size.h"
#include "common/staged_file.h"
#include "slam/camera/lens_distortion.h"
#include "slam/data/map_point.h"
#include "slam/place/vocabulary_file.h"

namespace depot::slam {
namespace {

constexpr char kMagic[8] = {'D', 'E', 'P', 'O', 'T', 'M', 'A', 'P'};
// Version 2 adds the lens distortion to the camera; version 3 the atlas
// (each keyframe's map and origin flag, each point's map). Older files
// still load (version 1: no distortion; before 3: one map).
constexpr uint32_t kVersion = 3;
constexpr uint32_t kOldestVersion = 1;
constexpr int kDescriptorBytes = 32;

void put_pose(BinaryWriter& out, const Pose& T) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out.put<double>(T.matrix()(r, c));
}

Pose take_pose(BinaryReader& in) {
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = in.take<double>();
  return T;
}

void put_camera(BinaryWriter& out, const PinholeCamera& c) {
  out.put<int32_t>(c.width);
  out.put<int32_t>(c.height);
  for (double v : {c.fx, c.fy, c.cx, c.cy, c.bf}) out.put<double>(v);
  for (double v : {c.lens.k1, c.lens.k2, c.lens.p1, c.lens.p2, c.lens.k3}) out.put<double>(v);
}

bool same_camera(const PinholeCamera& a, const PinholeCamera& b) {
  auto close = [](double x, double y) {
    return std::abs(x - y) <= 1e-6 * std::max(1.0, std::abs(x));
  };
  return a.width == b.width && a.height == b.height && close(a.fx, b.fx) && close(a.fy, b.fy) &&
         close(a.cx, b.cx) && close(a.cy, b.cy) && close(a.bf, b.bf) &&
         close(a.lens.k1, b.lens.k1) && close(a.lens.k2, b.lens.k2) &&
         close(a.lens.p1, b.lens.p1) && close(a.lens.p2, b.lens.p2) && close(a.lens.k3, b.lens.k3);
}

std::string describe(const PinholeCamera& c) {
  std::ostringstream s;
  s << c.width << "x" << c.height << " fx " << c.fx << " fy " << c.fy << " cx " << c.cx << " cy "
    << c.cy;
  if (c.distorted())
    s << " " << describe_lens(c.lens);
  else
    s << " no distortion";
  return s.str();
}

}  // namespace

void save_map_file(const Map& map, const PinholeCamera& camera, const ScaleLevels& levels,
                   uint32_t vocabulary_identity, const std::string& path) {
  const std::vector<const KeyFrame*> keyframes(map.keyframes().begin(), map.keyframes().end());
  BinaryWriter out;
  out.put_bytes(kMagic, sizeof(kMagic));
  out.put<uint32_t>(kVersion);
  out.put<uint32_t>(vocabulary_identity);
  put_camera(out, camera);
  out.put<int32_t>(levels.n_levels);
  out.put<float>(levels.scale_factor);

  out.put<uint32_t>(static_cast<uint32_t>(keyframes.size()));
  for (const KeyFrame* kf : keyframes) {
    const Features& f = kf->features;
    out.put<int64_t>(kf->id);
    out.put<int64_t>(kf->frame_id);
    out.put<double>(kf->timestamp);
    out.put<int32_t>(kf->map_id);
    out.put<uint8_t>(kf->map_origin ? 1 : 0);
    put_pose(out, kf->T_cw);
    const KeyFrame* parent = kf->parent();
    out.put<int64_t>(parent && !parent->bad ? parent->id : -1);
    std::vector<int64_t> loops;
    for (const KeyFrame* l : kf->loop_edges)
      if (!l->bad) loops.push_back(l->id);
    out.put<uint32_t>(static_cast<uint32_t>(loops.size()));
    for (int64_t id : loops) out.put<int64_t>(id);
    const std::vector<KeyFrame*> covisible = kf->covisibles();
    out.put<uint32_t>(static_cast<uint32_t>(covisible.size()));
    for (KeyFrame* c : covisible) {
      out.put<int64_t>(c->id);
      out.put<int32_t>(kf->weight(c));
    }
    out.put<uint32_t>(static_cast<uint32_t>(f.size()));
    for (size_t i = 0; i < f.size(); ++i) {
      const cv::KeyPoint& k = f.keypoints[i];
      for (float v : {k.pt.x, k.pt.y, k.size, k.angle, k.response}) out.put<float>(v);
      out.put<int32_t>(k.octave);
      out.put<float>(f.depth[i]);
      const cv::Vec3b colour = i < f.colours.size() ? f.colours[i] : cv::Vec3b(0, 0, 0);
      out.put_bytes(colour.val, 3);
      const MapPoint* mp = kf->map_points[i];
      out.put<int64_t>(mp && !mp->bad && mp->n_observations() > 0 ? mp->id : -1);
    }
    for (size_t i = 0; i < f.size(); ++i)
      out.put_bytes(f.descriptors.ptr<uint8_t>(static_cast<int>(i)), kDescriptorBytes);
  }

  // A point no keyframe observes any more (its observations culled) is no
  // part of the map: neither saved, counted by `map info`, nor exported.
  std::vector<const MapPoint*> points;
  for (const MapPoint* mp : map.map_points())
    if (!mp->bad && mp->n_observations() > 0) points.push_back(mp);
  out.put<uint32_t>(static_cast<uint32_t>(points.size()));
  for (const MapPoint* mp : points) {
    out.put<int64_t>(mp->id);
    out.put<int32_t>(mp->map_id);
    for (int k = 0; k < 3; ++k) out.put<double>(mp->position[k]);
    out.put<int64_t>(mp->reference && !mp->reference->bad ? mp->reference->id : -1);
    out.put<int64_t>(mp->first_keyframe_id);
    out.put<int32_t>(mp->visible);
    out.put<int32_t>(mp->found);
    static const uint8_t kNoDescriptor[kDescriptorBytes] = {};
    const bool has_descriptor = mp->descriptor.total() == kDescriptorBytes;
    out.put_bytes(has_descriptor ? mp->descriptor.ptr<uint8_t>(0) : kNoDescriptor,
                  kDescriptorBytes);
    for (int k = 0; k < 3; ++k) out.put<double>(mp->normal[k]);
    out.put<float>(mp->min_distance);
    out.put<float>(mp->max_distance);
  }
  out.put_checksum();

  StagedFile file(path);
  file.stream().write(out.bytes().data(), static_cast<std::streamsize>(out.bytes().size()));
  file.commit();
}

namespace {

// A map id of the atlas: small and not negative.
int32_t take_map_id(BinaryReader& in, const std::string& path, const std::string& what) {
  const int32_t id = in.take<int32_t>();
  if (id < 0 || id > 1000000)
    fail(path, "corrupt map (" + what + " in map " + std::to_string(id) + ")");
  return id;
}

// Reads the file into `bytes` and checks its header and checksum.
MapFileInfo read_header(const std::string& path, std::string& bytes) {
  bytes = read_binary_file(path, "map");
  if (bytes.size() < sizeof(kMagic) || bytes.compare(0, sizeof(kMagic), kMagic, sizeof(kMagic)))
    fail(path, "not a depot map (no DEPOTMAP header; write one with `depot slam run --save-map`)");
  MapFileInfo info;
  BinaryReader in(bytes, path, "map", sizeof(kMagic));
  info.version = in.take<uint32_t>();
  if (info.version < kOldestVersion || info.version > kVersion)
    fail(path, "map format version " + std::to_string(info.version) + ", this build reads " +
                   std::to_string(kOldestVersion) + " to " + std::to_string(kVersion));
  if (bytes.size() < sizeof(kMagic) + 8 + 4) fail(path, "truncated map");
  if (BinaryReader(bytes, path, "map", bytes.size() - 4).take<uint32_t>() !=
      crc32_of(bytes, bytes.size() - 4))
    fail(path, "corrupt or truncated map (checksum mismatch)");
  info.vocabulary = in.take<uint32_t>();
  info.camera.width = in.take<int32_t>();
  info.camera.height = in.take<int32_t>();
  for (double* v :
       {&info.camera.fx, &info.camera.fy, &info.camera.cx, &info.camera.cy, &info.camera.bf})
    *v = in.take<double>();
  if (info.version >= 2)
    for (double* v : {&info.camera.lens.k1, &info.camera.lens.k2, &info.camera.lens.p1,
                      &info.camera.lens.p2, &info.camera.lens.k3})
      *v = in.take<double>();
  info.levels = in.take<int32_t>();
  info.scale_factor = in.take<float>();
  const PinholeCamera& c = info.camera;
  if (!image_size_ok(c.width, c.height) ||
      !(c.fx > 0 && c.fy > 0 && std::isfinite(c.fx) && std::isfinite(c.fy) && std::isfinite(c.cx) &&
        std::isfinite(c.cy) && std::isfinite(c.bf) && std::isfinite(c.lens.k1) &&
        std::isfinite(c.lens.k2) && std::isfinite(c.lens.p1) && std::isfinite(c.lens.p2) &&
        std::isfinite(c.lens.k3)))
    fail(path,
         "corrupt map (camera " + std::to_string(c.width) + "x" + std::to_string(c.height) + ")");
  if (info.levels < 1 || info.levels > 32 || !(info.scale_factor > 1.0f))
    fail(path, "corrupt map (ORB pyramid of " + std::to_string(info.levels) + " levels)");
  set_undistorted_bounds(info.camera, path);
  info.header_bytes = in.at();
  return info;
}

// Everything after the header, into `map`; `camera` and `levels` are the
// keyframes' (checked against the file by the callers).
void read_body(const std::string& bytes, const std::string& path, MapFileInfo& info,
               const PinholeCamera& camera, const ScaleLevels& levels, Map& map)
    DEPOT_REQUIRES(map.mutex()) {
  if (map.n_keyframes() > 0) fail(path, "a map can only be loaded before any frame is tracked");
  BinaryReader in(bytes, path, "map", info.header_bytes);

  struct KeyFrameRecord {
    KeyFrame* kf;
    int64_t parent;
    std::vector<int64_t> loops, points;
    std::vector<std::pair<int64_t, int>> covisible;
  };
  std::vector<KeyFrameRecord> records;
  std::unordered_map<int64_t, KeyFrame*> kf_by_id;
  const uint32_t n_keyframes = in.take<uint32_t>();
  for (uint32_t k = 0; k < n_keyframes; ++k) {
    KeyFrameRecord r;
    const int64_t id = in.take<int64_t>();
    const int64_t frame_id = in.take<int64_t>();
    const double timestamp = in.take<double>();
    int32_t map_id = 0;
    bool origin = k == 0;
    if (info.version >= 3) {
      map_id = take_map_id(in, path, "keyframe " + std::to_string(id));
      origin = in.take<uint8_t>() != 0;
    }
    const Pose T_cw = take_pose(in);
    r.parent = in.take<int64_t>();
    const uint32_t n_loops = in.take<uint32_t>();
    if (static_cast<uint64_t>(n_loops) * 8 > in.left())
      fail(path, "truncated map (keyframe " + std::to_string(id) + " claims " +
                     std::to_string(n_loops) + " loop edges)");
    r.loops.resize(n_loops);
    for (int64_t& l : r.loops) l = in.take<int64_t>();
    const uint32_t n_covisible = in.take<uint32_t>();
    if (static_cast<uint64_t>(n_covisible) * 12 > in.left()) fail(path, "truncated map");
    r.covisible.resize(n_covisible);
    for (auto& [other, weight] : r.covisible) {
      other = in.take<int64_t>();
      weight = in.take<int32_t>();
    }
    const uint32_t n = in.take<uint32_t>();
    if (static_cast<uint64_t>(n) * (7 * 4 + 3 + 8 + kDescriptorBytes) > in.left())
      fail(path, "truncated map (keyframe " + std::to_string(id) + " claims " + std::to_string(n) +
                     " keypoints)");
    std::vector<cv::KeyPoint> keypoints(n);
    std::vector<float> depth(n);
    std::vector<cv::Vec3b> colours(n);
    r.points.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      cv::KeyPoint& kp = keypoints[i];
      kp.pt.x = in.take<float>();
      kp.pt.y = in.take<float>();
      kp.size = in.take<float>();
      kp.angle = in.take<float>();
      kp.response = in.take<float>();
      kp.octave = in.take<int32_t>();
      // Near the image (also no NaN): the keyframe's grid indexes by it.
      const float w = static_cast<float>(camera.width), h = static_cast<float>(camera.height);
      if (!(kp.pt.x >= -w && kp.pt.x <= 2 * w && kp.pt.y >= -h && kp.pt.y <= 2 * h))
        fail(path, "corrupt map (keyframe " + std::to_string(id) + ": keypoint " +
                       std::to_string(i) + " far outside the image)");
      if (kp.octave < 0 || kp.octave >= levels.n_levels)
        fail(path, "corrupt map (keyframe " + std::to_string(id) + ": octave " +
                       std::to_string(kp.octave) + ")");
      depth[i] = in.take<float>();
      in.take_bytes(colours[i].val, 3);
      r.points[i] = in.take<int64_t>();
    }
    cv::Mat descriptors(static_cast<int>(n), kDescriptorBytes, CV_8U);
    for (uint32_t i = 0; i < n; ++i)
      in.take_bytes(descriptors.ptr<uint8_t>(static_cast<int>(i)), kDescriptorBytes);
    Frame frame(frame_id, timestamp,
                Features(std::move(keypoints), descriptors, std::move(depth), camera, &levels));
    frame.features.colours = std::move(colours);
    frame.T_cw = T_cw;
    frame.has_pose = true;
    map.activate(map_id);
    r.kf = map.create_keyframe(frame);
    r.kf->map_origin = origin;
    if (!kf_by_id.emplace(id, r.kf).second)
      fail(path, "corrupt map (keyframe " + std::to_string(id) + " twice)");
    records.push_back(std::move(r));
  }

  std::unordered_map<int64_t, MapPoint*> mp_by_id;
  const uint32_t n_points = in.take<uint32_t>();
  for (uint32_t p = 0; p < n_points; ++p) {
    const int64_t id = in.take<int64_t>();
    const int32_t map_id =
        info.version >= 3 ? take_map_id(in, path, "point " + std::to_string(id)) : 0;
    Eigen::Vector3d x;
    for (int k = 0; k < 3; ++k) x[k] = in.take<double>();
    const int64_t reference = in.take<int64_t>();
    const auto ref = kf_by_id.find(reference);
    MapPoint* mp = map.create_map_point(x, ref == kf_by_id.end() ? nullptr : ref->second);
    mp->map_id = map_id;
    const int64_t first_keyframe = in.take<int64_t>();
    const auto first = kf_by_id.find(first_keyframe);
    mp->first_keyframe_id = first == kf_by_id.end() ? 0 : first->second->id;
    mp->visible = in.take<int32_t>();
    mp->found = in.take<int32_t>();
    mp->descriptor = cv::Mat(1, kDescriptorBytes, CV_8U);
    in.take_bytes(mp->descriptor.ptr<uint8_t>(0), kDescriptorBytes);
    for (int k = 0; k < 3; ++k) mp->normal[k] = in.take<double>();
    mp->min_distance = in.take<float>();
    mp->max_distance = in.take<float>();
    if (!mp_by_id.emplace(id, mp).second)
      fail(path, "corrupt map (point " + std::to_string(id) + " twice)");
  }
  if (in.left() != 4)
    fail(path, "corrupt map (" + std::to_string(in.left() - 4) + " unexpected bytes)");

  // Observations, covisibility and the spanning tree as they were: the
  // loaded map is the saved one, not a recomputation of it.
  for (KeyFrameRecord& r : records)
    for (size_t i = 0; i < r.points.size(); ++i) {
      if (r.points[i] < 0) continue;
      const auto it = mp_by_id.find(r.points[i]);
      if (it == mp_by_id.end())
        fail(path, "corrupt map (a keyframe sees point " + std::to_string(r.points[i]) +
                       ", which is not in it)");
      if (it->second->map_id != r.kf->map_id)
        fail(path, "corrupt map (keyframe " + std::to_string(r.kf->id) + " of map " +
                       std::to_string(r.kf->map_id) + " sees a point of map " +
                       std::to_string(it->second->map_id) + ")");
      it->second->add_observation(r.kf, i);
      r.kf->add_map_point(it->second, i);
    }
  for (MapPoint* mp : map.map_points())
    if (!mp->reference && !mp->observations.empty())
      mp->reference = mp->observations.begin()->first;
  for (KeyFrameRecord& r : records) {
    for (const auto& [other, weight] : r.covisible)
      if (const auto it = kf_by_id.find(other); it != kf_by_id.end())
        r.kf->add_connection(it->second, weight);
    const auto parent = kf_by_id.find(r.parent);
    if (parent != kf_by_id.end()) r.kf->set_parent(parent->second);
    for (int64_t l : r.loops)
      if (const auto it = kf_by_id.find(l); it != kf_by_id.end())
        r.kf->loop_edges.insert(it->second);
  }
  map.restore_atlas();
  info.keyframes = map.n_keyframes();
  info.points = map.n_map_points();
  info.maps = map.map_ids().size();
}

}  // namespace

MapFileInfo load_map_file(const std::string& path, const PinholeCamera& camera,
                          const ScaleLevels& levels, uint32_t vocabulary_identity, Map& map) {
  std::string bytes;
  MapFileInfo info = read_header(path, bytes);
  if (info.vocabulary != vocabulary_identity)
    fail(path, "map built with another vocabulary (identity " +
                   format_vocabulary_identity(info.vocabulary) + ", this run's is " +
                   format_vocabulary_identity(vocabulary_identity) +
                   "; run with the vocabulary that made it, --vocabulary F)");
  if (!same_camera(info.camera, camera))
    fail(path, "map made with another camera (" + describe(info.camera) + "; this dataset's is " +
                   describe(camera) + ")");
  if (info.levels != levels.n_levels || std::abs(info.scale_factor - levels.scale_factor) > 1e-6f)
    fail(path, "map made with another ORB pyramid (" + std::to_string(info.levels) +
                   " levels, scale " + std::to_string(info.scale_factor) + ")");
  read_body(bytes, path, info, camera, levels, map);
  return info;
}

MapFileInfo load_map_file_as_saved(const std::string& path, ScaleLevels& levels, Map& map) {
  std::string bytes;
  MapFileInfo info = read_header(path, bytes);
  levels = ScaleLevels::make(info.levels, info.scale_factor);
  read_body(bytes, path, info, info.camera, levels, map);
  return info;
}

}  // namespace depot::slam
