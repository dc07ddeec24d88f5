#include "slam/io/ply_file.h"

#include <cstdint>

#include "common/binary_io.h"
#include "common/staged_file.h"

namespace depot::slam {

void write_ply(const std::string& path, const std::vector<PlyPoint>& points,
               const std::string& count_name) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment depot-slam\nelement vertex " +
                       std::to_string(points.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\n"
                       "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (!count_name.empty()) header += "property int " + count_name + "\n";
  header += "end_header\n";
  BinaryWriter out;
  out.put_bytes(header.data(), header.size());
  for (const PlyPoint& p : points) {
    for (int k = 0; k < 3; ++k) out.put<float>(p.position[k]);
    for (int c : {2, 1, 0}) out.put<uint8_t>(p.bgr[c]);  // BGR -> RGB
    if (!count_name.empty()) out.put<int32_t>(p.count);
  }
  StagedFile file(path);
  file.stream().write(out.bytes().data(), static_cast<std::streamsize>(out.bytes().size()));
  file.commit();
}

}  // namespace depot::slam
