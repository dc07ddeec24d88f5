#pragma once
// Numbers in text people read (error messages, labels): printf's %g, six
// significant digits and no trailing zeros (0.5, 1e-06, 30; not 0.500000).
#include <string>

namespace depot {

std::string shortest_number(double value);

// `decimals` digits after the point (fmt's {:.Nf}), or "-" when not finite.
std::string fixed_number(double value, int decimals);

// A length with two decimals and its unit: "1.50 m".
std::string metres_text(double value);

}  // namespace depot
