#include "dataset/text_fields.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "common/error.h"

namespace depot::dataset {

double parse_number_field(const std::string& text, const char* field, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(v))
    fail(where, std::string(field) + " '" + text + "' is not a number");
  return v;
}

long parse_integer_field(const std::string& text, const char* field, const std::string& where) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE)
    fail(where, std::string(field) + " '" + text + "' is not an integer");
  return v;
}

bool parse_flag_field(const std::string& text, const char* field, const std::string& where) {
  if (text != "0" && text != "1") fail(where, std::string(field) + " '" + text + "' is not 0 or 1");
  return text == "1";
}

}  // namespace depot::dataset
