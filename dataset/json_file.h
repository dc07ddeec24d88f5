#pragma once
// Reading the dataset's JSON files (info.json, objects.json) with errors
// that name the file, and the line for a syntax error, in one line.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace depot::dataset {

// The parsed file. Throws depot::Error "<path>: cannot open file (<what>)"
// or "<path>:<line>: not valid JSON: <problem>".
nlohmann::json read_json_file(const std::string& path, const std::string& what);

// Typed members of a JSON object. Each throws depot::Error
// "<where>: '<key>' is missing" or "<where>: '<key>' is not <a kind>", where
// `where` names the file and the object (e.g. "objects.json: instance 3").
std::string string_member(const nlohmann::json& object, const char* key, const std::string& where);
long long integer_member(const nlohmann::json& object, const char* key, const std::string& where);
double number_member(const nlohmann::json& object, const char* key, const std::string& where);
// An array of exactly `size` numbers.
std::vector<double> numbers_member(const nlohmann::json& object, const char* key, size_t size,
                                   const std::string& where);

}  // namespace depot::dataset
