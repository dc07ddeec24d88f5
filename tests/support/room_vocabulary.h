#pragma once
// A small place-recognition vocabulary trained inside the test run, so the
// SLAM core's tests need neither outside data nor the vocabulary the build
// trains: ORB descriptors of views of the synthetic room
// (synthetic_room.h) with another texture seed than the tests' frames, so
// their frames are not its training images.
#include <memory>
#include <string>

#include "slam/place/vocabulary.h"

namespace depot::test {

// Trained once per process (branching 6, 4 levels; deterministic).
std::shared_ptr<const slam::Vocabulary> room_vocabulary();

// The same vocabulary saved to a file once per process (for System, which
// loads its vocabulary from the settings' path); removed at exit.
const std::string& room_vocabulary_file();

}  // namespace depot::test
