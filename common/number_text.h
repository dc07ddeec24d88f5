#pragma once
// Numbers in text people read (error messages, labels): printf's %g, six
// significant digits and no trailing zeros (0.5, 1e-06, 30; not 0.500000).
#include <string>

namespace depot {

std::string shortest_number(double value);

}  // namespace depot
