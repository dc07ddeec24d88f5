#pragma once
// What tracking needs from local mapping: hand over keyframes and ask
// whether it is ready for more. Keeps the tracker independent of the
// mapper's threading.
#include <cstddef>

namespace depot::slam {

class KeyFrame;

class KeyFrameSink {
 public:
  virtual ~KeyFrameSink() = default;
  virtual void insert_keyframe(KeyFrame* kf) = 0;
  virtual bool idle() const = 0;      // waiting for work
  virtual size_t queued() const = 0;  // keyframes not processed yet
  virtual void interrupt_ba() = 0;    // ask a running bundle adjustment to stop early
};

}  // namespace depot::slam
