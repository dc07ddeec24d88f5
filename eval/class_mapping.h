#pragma once
// How a detector's labels count against the ground truth's classes, read
// from a YAML file (scenes/detectors/coco_to_depot.yaml):
//
//   map:                 # detector label -> ground-truth class
//     person: person
//     diningtable: desk
//   any_animal:          # truth classes the detector has no label for ...
//     classes: [pig]
//     labels: [dog, cat, sheep, cow, horse, bird, bear]   # ... matched by any of these
//
// A label not in `map` counts as itself ("sheep" matches a "sheep" box). A
// box of an `any_animal` class is matched by a detection with any of the
// listed labels (pig is not a COCO class: a pig seen as sheep or dog is
// found). The default mapping is the identity (the simulated detector's
// labels are the simulator's classes).
#include <string>
#include <vector>

namespace depot::eval {

class ClassMapping {
 public:
  ClassMapping() = default;
  // Throws depot::Error "<path>[:line]: <problem>" for an unreadable file, a
  // YAML error, an unknown key or an entry that is not a name.
  static ClassMapping load(const std::string& path);

  // The class a detection with this label counts as.
  std::string class_of(const std::string& label) const;
  // Whether a detection with this label matches a box of `truth_class`.
  bool matches(const std::string& label, const std::string& truth_class) const;
  // Whether some label of `labels` (a detector's class list) can match a
  // box of `truth_class`.
  bool reachable(const std::string& truth_class, const std::vector<std::string>& labels) const;
  // Whether a detection with this label could stand for an object of one of
  // `classes` (its class is one, or it is an any-animal label and one of
  // `classes` is an any-animal class): the detections precision counts.
  bool relevant(const std::string& label, const std::vector<std::string>& classes) const;

  // Throws depot::Error "<path>:<line>: class 'x' is not a class of <what>
  // (a, b, ...)" when a mapped-to or any-animal class is not in `classes`.
  void check_classes(const std::vector<std::string>& classes, const std::string& what) const;

  const std::string& path() const { return path_; }  // "" for the identity

 private:
  struct Entry {
    std::string from, to;
    int line = 0;
  };
  struct Named {
    std::string name;
    int line = 0;
  };
  std::string path_;
  std::vector<Entry> map_;
  std::vector<Named> animal_classes_;
  std::vector<std::string> animal_labels_;
};

}  // namespace depot::eval
