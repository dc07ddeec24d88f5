#include "sim/sensor/noise_table.h"

#include <algorithm>
#include <cmath>

namespace depot::sim {

const std::vector<int8_t>& unit_noise_table() {
  static const std::vector<int8_t> table = [] {
    std::vector<int8_t> t(1 << 20);
    Rng rng(0x6e015e);
    for (auto& v : t)
      v = static_cast<int8_t>(std::clamp(std::lround(16.0 * rng.normal()), -127L, 127L));
    return t;
  }();
  return table;
}

const int8_t* noise_row(Rng& rng, size_t count) {
  const auto& table = unit_noise_table();
  size_t offset = rng.next_u64() & (table.size() - 1);
  if (offset + count > table.size()) offset = table.size() - count;
  return table.data() + offset;
}

}  // namespace depot::sim
