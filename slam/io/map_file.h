#pragma once
// The saved map (`depot slam run --save-map M`, `--load-map M`): a versioned
// binary file of the map's keyframes (pose, keypoints with depth and
// descriptors, which map point each keypoint sees, spanning-tree parent,
// loop edges, covisible keyframes with their weights) and map points
// (position, reference keyframe, descriptor, viewing direction and range),
// with the camera, the ORB pyramid and the vocabulary's identity it was
// built with, ending in a CRC-32 of everything before it. Bad keyframes and
// points are left out. Loading restores the map as it was, nothing
// recomputed, so a loaded map tracks as the one in memory does.
//
// Layout (little-endian): "DEPOTMAP", u32 version, u32 vocabulary identity,
// camera (i32 width, height; f64 fx, fy, cx, cy, bf; from version 2 f64 k1,
// k2, p1, p2, k3; keypoints are stored undistorted), i32 pyramid levels,
// f32 scale factor, u32 keyframe count, keyframes, u32 point count, points,
// u32 CRC-32. From version 3 a keyframe holds its map (i32) and origin flag
// (u8) after its timestamp and a point its map (i32) after its id: every map
// of the atlas is saved and loaded as it was.
#include <cstdint>
#include <string>

#include "slam/camera/pinhole_camera.h"
#include "slam/data/map.h"

namespace depot::slam {

struct MapFileInfo {
  uint32_t version = 0;
  uint32_t vocabulary = 0;  // identity of the vocabulary it was built with
  PinholeCamera camera;
  int levels = 0;
  float scale_factor = 0;
  size_t keyframes = 0, points = 0;  // after loading
  size_t maps = 0;                   // maps of the atlas, after loading
  size_t header_bytes = 0;
};

// Writes the map's good keyframes and points, every map of the atlas with
// its id and origin, through a staged file (a failure leaves no file, and no
// half file ever replaces an old one). The caller holds map.mutex().
void save_map_file(const Map& map, const PinholeCamera& camera, const ScaleLevels& levels,
                   uint32_t vocabulary_identity, const std::string& path)
    DEPOT_REQUIRES(map.mutex());

// Reads a saved map into `map`, which must be empty; keyframes and points
// are renumbered in their saved order. Throws depot::Error naming the file
// for a missing file, another format, a truncated or corrupt file
// (checksum), another version, and a map built with another vocabulary,
// camera or ORB pyramid than the run's. The caller holds map.mutex().
MapFileInfo load_map_file(const std::string& path, const PinholeCamera& camera,
                          const ScaleLevels& levels, uint32_t vocabulary_identity, Map& map)
    DEPOT_REQUIRES(map.mutex());

// Reads a saved map with what it was built with (its camera, its ORB
// pyramid, which `levels` receives and the keyframes then point to; any
// vocabulary), for tools that inspect or export it. Same errors otherwise.
MapFileInfo load_map_file_as_saved(const std::string& path, ScaleLevels& levels, Map& map)
    DEPOT_REQUIRES(map.mutex());

}  // namespace depot::slam
