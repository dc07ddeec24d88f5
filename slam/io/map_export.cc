#include "slam/io/map_export.h"

#include "slam/data/map_point.h"

namespace depot::slam {

std::vector<PlyPoint> map_point_cloud(const Map& map) {
  std::vector<PlyPoint> cloud;
  cloud.reserve(map.n_map_points());
  for (const MapPoint* mp : map.map_points()) {
    if (mp->bad || mp->observations.empty()) continue;
    PlyPoint p;
    p.position = mp->position.cast<float>();
    p.bgr = cv::Vec3b(0, 0, 0);
    const auto it = mp->reference ? mp->observations.find(mp->reference) : mp->observations.end();
    const auto& [kf, index] = it != mp->observations.end() ? *it : *mp->observations.begin();
    if (index < kf->features.colours.size()) p.bgr = kf->features.colours[index];
    p.count = mp->n_observations();
    cloud.push_back(p);
  }
  return cloud;
}

}  // namespace depot::slam
