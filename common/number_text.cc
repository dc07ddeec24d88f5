#include "common/number_text.h"

#include <sstream>

namespace depot {

std::string shortest_number(double value) {
  std::ostringstream text;  // the classic locale's default: %g
  text << value;
  return text.str();
}

}  // namespace depot
