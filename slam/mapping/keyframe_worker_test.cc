#include "slam/mapping/keyframe_worker.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace depot::slam {
namespace {

// The worker never looks into a keyframe: distinct addresses stand for them.
struct Tokens {
  std::vector<char> storage = std::vector<char>(16);
  KeyFrame* at(int i) { return reinterpret_cast<KeyFrame*>(&storage[i]); }
};

struct Recorder {
  std::mutex mutex;
  std::vector<KeyFrame*> seen;
  std::vector<std::thread::id> threads;
  void operator()(KeyFrame* kf) {
    std::lock_guard<std::mutex> lock(mutex);
    seen.push_back(kf);
    threads.push_back(std::this_thread::get_id());
  }
  size_t count() {
    std::lock_guard<std::mutex> lock(mutex);
    return seen.size();
  }
};

// A threaded worker whose step takes 20 ms, and says when one is running.
struct SlowWorker {
  Tokens t;
  Recorder rec;
  std::atomic<bool> in_step{false};
  KeyFrameWorker worker{true, [this](KeyFrame* kf) {
                          in_step = true;
                          std::this_thread::sleep_for(std::chrono::milliseconds(20));
                          rec(kf);
                          in_step = false;
                        }};
  void wait_for_a_step() {
    while (!in_step) std::this_thread::yield();
  }
};

void wait_until_idle(const KeyFrameWorker& worker) {
  for (int i = 0; i < 5000 && !worker.idle(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

TEST(KeyFrameWorker, SynchronousRunsOnTheCallersThreadInOrder) {
  Tokens t;
  Recorder rec;
  KeyFrameWorker worker(false, [&](KeyFrame* kf) { rec(kf); });
  for (int i = 0; i < 5; ++i) worker.push(t.at(i));
  EXPECT_EQ(worker.queued(), 5u);
  EXPECT_EQ(rec.count(), 0u);  // nothing happens until run_pending
  worker.run_pending();
  ASSERT_EQ(rec.seen.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(rec.seen[i], t.at(i));
    EXPECT_EQ(rec.threads[i], std::this_thread::get_id());
  }
  EXPECT_TRUE(worker.idle());
}

TEST(KeyFrameWorker, ThreadedRunsOnItsOwnThreadInOrder) {
  Tokens t;
  Recorder rec;
  KeyFrameWorker worker(true, [&](KeyFrame* kf) { rec(kf); });
  for (int i = 0; i < 10; ++i) worker.push(t.at(i));
  wait_until_idle(worker);
  worker.stop();
  ASSERT_EQ(rec.seen.size(), 10u);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(rec.seen[i], t.at(i));
    EXPECT_NE(rec.threads[i], std::this_thread::get_id());
  }
}

TEST(KeyFrameWorker, StopFinishesTheQueue) {
  Tokens t;
  Recorder rec;
  KeyFrameWorker worker(true, [&](KeyFrame* kf) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    rec(kf);
  });
  for (int i = 0; i < 8; ++i) worker.push(t.at(i));
  worker.stop();
  EXPECT_EQ(rec.count(), 8u);
}

TEST(KeyFrameWorker, PauseHoldsQueuedKeyFramesUntilResume) {
  SlowWorker w;
  w.worker.push(w.t.at(0));
  w.wait_for_a_step();
  w.worker.pause();  // returns only once the running step is done
  EXPECT_FALSE(w.in_step);
  EXPECT_EQ(w.rec.count(), 1u);
  EXPECT_TRUE(w.worker.pause_requested());
  w.worker.push(w.t.at(1));
  w.worker.push(w.t.at(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(w.rec.count(), 1u);
  EXPECT_EQ(w.worker.queued(), 2u);
  EXPECT_FALSE(w.worker.idle());
  w.worker.resume();
  wait_until_idle(w.worker);
  EXPECT_EQ(w.rec.count(), 3u);
}

TEST(KeyFrameWorker, AFailureStopsTheWorkerAndIsKept) {
  for (const bool threaded : {false, true}) {
    Tokens t;
    Recorder rec;
    KeyFrameWorker worker(threaded, [&](KeyFrame* kf) {
      if (kf == t.at(1)) throw std::runtime_error("broken keyframe");
      rec(kf);
    });
    for (int i = 0; i < 4; ++i) worker.push(t.at(i));
    if (threaded) {
      wait_until_idle(worker);
    } else {
      EXPECT_THROW(worker.run_pending(), std::runtime_error);
      EXPECT_THROW(worker.run_pending(), std::runtime_error);  // again, not forgotten
    }
    ASSERT_TRUE(worker.failure());
    EXPECT_EQ(rec.count(), 1u);  // the queue behind the failure is dropped
    EXPECT_EQ(worker.queued(), 0u);
    EXPECT_TRUE(worker.idle());
    EXPECT_FALSE(worker.push(t.at(5)));
    try {
      std::rethrow_exception(worker.failure());
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "broken keyframe");
    }
  }
}

TEST(KeyFrameWorker, ClearDropsQueuedKeyFramesAndWaitsForTheRunningOne) {
  SlowWorker w;
  for (int i = 0; i < 6; ++i) w.worker.push(w.t.at(i));
  w.wait_for_a_step();
  w.worker.clear();
  EXPECT_FALSE(w.in_step);
  EXPECT_EQ(w.worker.queued(), 0u);
  w.worker.stop();
  EXPECT_LT(w.rec.count(), 6u);
  EXPECT_GE(w.rec.count(), 1u);
}

}  // namespace
}  // namespace depot::slam
