#include "dataset/json_file.h"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "common/error.h"

namespace depot::dataset {
namespace {

// nlohmann's message without its "[json.exception.parse_error.101] " tag.
std::string plain_message(const std::exception& e) {
  std::string m = e.what();
  if (!m.empty() && m[0] == '[') {
    const auto end = m.find("] ");
    if (end != std::string::npos) m = m.substr(end + 2);
  }
  return m;
}

const nlohmann::json& member(const nlohmann::json& object, const char* key,
                             const std::string& where) {
  if (!object.is_object()) fail(where, "is not a JSON object");
  const auto it = object.find(key);
  if (it == object.end()) fail(where, std::string("'") + key + "' is missing");
  return *it;
}

[[noreturn]] void wrong_kind(const char* key, const char* kind, const std::string& where) {
  fail(where, std::string("'") + key + "' is not " + kind);
}

}  // namespace

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file (" + what + ")");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // The line of the byte where parsing stopped (1-based).
    const size_t end = std::min(text.size(), e.byte > 0 ? e.byte - 1 : 0);
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(end), '\n');
    fail(path + ":" + std::to_string(line), "not valid JSON: " + plain_message(e));
  } catch (const nlohmann::json::exception& e) {
    // E.g. a number too large for a double.
    fail(path, "not valid JSON: " + plain_message(e));
  }
}

std::string string_member(const nlohmann::json& object, const char* key, const std::string& where) {
  const nlohmann::json& v = member(object, key, where);
  if (!v.is_string()) wrong_kind(key, "a string", where);
  return v.get<std::string>();
}

long long integer_member(const nlohmann::json& object, const char* key, const std::string& where) {
  const nlohmann::json& v = member(object, key, where);
  if (!v.is_number_integer()) wrong_kind(key, "a whole number", where);
  return v.get<long long>();
}

double number_member(const nlohmann::json& object, const char* key, const std::string& where) {
  const nlohmann::json& v = member(object, key, where);
  if (!v.is_number()) wrong_kind(key, "a number", where);
  return v.get<double>();
}

std::vector<double> numbers_member(const nlohmann::json& object, const char* key, size_t size,
                                   const std::string& where) {
  const nlohmann::json& v = member(object, key, where);
  const std::string kind = "an array of " + std::to_string(size) + " numbers";
  if (!v.is_array() || v.size() != size) wrong_kind(key, kind.c_str(), where);
  std::vector<double> out;
  for (const nlohmann::json& x : v) {
    if (!x.is_number()) wrong_kind(key, kind.c_str(), where);
    out.push_back(x.get<double>());
  }
  return out;
}

}  // namespace depot::dataset
