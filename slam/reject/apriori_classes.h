#pragma once
// The a-priori motion class of each detected object class (PAPER.md,
// Table 1): dynamic, potentially dynamic, or static (everything not listed).
// Configuration, not code: loaded from YAML.
#include <set>
#include <string>
#include <vector>

namespace depot::slam {

enum class MotionClass { kStatic, kPotentiallyDynamic, kDynamic };

class AprioriClasses {
 public:
  AprioriClasses() = default;
  AprioriClasses(std::set<std::string> dynamic, std::set<std::string> potentially_dynamic);
  // YAML: `dynamic: [..]`, `potentially_dynamic: [..]`. Errors name the file.
  static AprioriClasses load(const std::string& path);

  MotionClass classify(const std::string& class_name) const;
  // Fails (depot::Error naming `table_name`) when the table lists a class the
  // detector cannot output.
  void check_against(const std::vector<std::string>& detector_classes,
                     const std::string& table_name, const std::string& detector_name) const;
  const std::set<std::string>& dynamic() const { return dynamic_; }
  const std::set<std::string>& potentially_dynamic() const { return potential_; }

 private:
  std::set<std::string> dynamic_, potential_;
};

}  // namespace depot::slam
