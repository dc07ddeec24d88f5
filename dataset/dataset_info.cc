#include "dataset/dataset_info.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"
#include "dataset/json_file.h"

namespace depot::dataset {
namespace {

std::optional<uint64_t> optional_seed(const nlohmann::json& doc, const char* key,
                                      const std::string& where) {
  const auto it = doc.find(key);
  if (it == doc.end()) return std::nullopt;
  if (!it->is_number_unsigned()) fail(where, std::string("'") + key + "' is not a seed (>= 0)");
  return it->get<uint64_t>();
}

template <typename T>
std::optional<T> optional_member(const nlohmann::json& doc, const char* key,
                                 const std::string& where,
                                 T (*read)(const nlohmann::json&, const char*,
                                           const std::string&)) {
  if (!doc.contains(key)) return std::nullopt;
  return read(doc, key, where);
}

long whole_number(const nlohmann::json& doc, const char* key, const std::string& where) {
  return static_cast<long>(integer_member(doc, key, where));
}

std::string text_or_empty(const nlohmann::json& doc, const char* key, const std::string& where) {
  return doc.contains(key) ? string_member(doc, key, where) : std::string();
}

template <typename T>
std::vector<std::pair<T, T>> pairs_member(const nlohmann::json& doc, const char* key,
                                          const std::string& where) {
  std::vector<std::pair<T, T>> out;
  const auto it = doc.find(key);
  if (it == doc.end()) return out;
  const std::string bad = std::string("'") + key + "' is not a list of [first, last] pairs";
  if (!it->is_array()) fail(where, bad);
  for (const nlohmann::json& p : *it) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) fail(where, bad);
    if (std::is_integral_v<T> && (!p[0].is_number_integer() || !p[1].is_number_integer()))
      fail(where, bad);
    out.emplace_back(p[0].get<T>(), p[1].get<T>());
  }
  return out;
}

}  // namespace

std::string format_info(const DatasetInfo& info) {
  // nlohmann's object keeps keys in name order: the bytes depend only on
  // the values.
  nlohmann::json doc = {{"format_version", kFormatVersion}, {"generator", info.generator},
                        {"scenario", info.scenario},        {"actors_style", info.actors_style},
                        {"props_style", info.props_style},  {"motion", info.motion}};
  if (info.description) doc["description"] = *info.description;
  if (info.seed) doc["seed"] = *info.seed;
  if (info.world_seed) doc["world_seed"] = *info.world_seed;
  if (info.frames) doc["frames"] = *info.frames;
  if (info.dynamic_load) doc["dynamic_load"] = *info.dynamic_load;
  if (info.sensor) doc["sensor"] = *info.sensor;
  if (!info.camera_cover.empty()) {
    nlohmann::json seconds = nlohmann::json::array(), frames = nlohmann::json::array();
    for (const auto& [start, end] : info.camera_cover) seconds.push_back({start, end});
    for (const auto& [first, last] : info.covered_frames) frames.push_back({first, last});
    doc["camera_cover"] = seconds;
    doc["covered_frames"] = frames;
  }
  return doc.dump(1) + "\n";
}

void write_info(const std::string& dataset_dir, const DatasetInfo& info) {
  write_text_file_atomic(dataset_file(dataset_dir, kInfoFile), format_info(info));
}

std::optional<DatasetInfo> read_info(const std::string& dataset_dir) {
  const std::string path = dataset_file(dataset_dir, kInfoFile);
  std::ifstream probe(path);
  if (!probe) return std::nullopt;
  const nlohmann::json doc = read_json_file(path, "the dataset's info");
  DatasetInfo info;
  info.format_version = checked_format_version(doc, path);
  // Every member is optional: older datasets and truth-only exports state
  // fewer. A member that is there must have its type.
  info.generator = text_or_empty(doc, "generator", path);
  info.scenario = text_or_empty(doc, "scenario", path);
  info.description = optional_member<std::string>(doc, "description", path, string_member);
  info.seed = optional_seed(doc, "seed", path);
  info.world_seed = optional_seed(doc, "world_seed", path);
  info.frames = optional_member<long>(doc, "frames", path, whole_number);
  info.dynamic_load = optional_member<double>(doc, "dynamic_load", path, number_member);
  info.actors_style = text_or_empty(doc, "actors_style", path);
  info.props_style = text_or_empty(doc, "props_style", path);
  info.sensor = optional_member<std::string>(doc, "sensor", path, string_member);
  info.motion = text_or_empty(doc, "motion", path);
  info.camera_cover = pairs_member<double>(doc, "camera_cover", path);
  info.covered_frames = pairs_member<long>(doc, "covered_frames", path);
  return info;
}

}  // namespace depot::dataset
