#include "common/number_text.h"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

namespace depot {

std::string shortest_number(double value) {
  std::ostringstream text;  // the classic locale's default: %g
  text << value;
  return text.str();
}

std::string fixed_number(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  return fmt::format("{:.{}f}", value, decimals);
}

std::string metres_text(double value) {
  return fmt::format("{:.2f} m", value);
}

}  // namespace depot
