#pragma once
// Orders keyframes and map points by id, not by address: containers keyed
// by pointers would otherwise iterate in heap order, which changes with
// unrelated allocations (other threads, the simulator in the same process)
// and makes runs irreproducible.

namespace depot::slam {

struct ById {
  template <typename T>
  bool operator()(const T* a, const T* b) const {
    return a->id < b->id;
  }
};

}  // namespace depot::slam
