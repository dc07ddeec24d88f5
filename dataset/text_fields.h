#pragma once
// Parsing the words of a dataset text record (common/text_records.h), each
// failure one line "<where>: <field> '<text>' is not ...".
#include <string>

namespace depot::dataset {

// A finite decimal number.
double parse_number_field(const std::string& text, const char* field, const std::string& where);
// A whole number (no fraction, no trailing characters).
long parse_integer_field(const std::string& text, const char* field, const std::string& where);
// "0" or "1".
bool parse_flag_field(const std::string& text, const char* field, const std::string& where);

}  // namespace depot::dataset
