#pragma once
// A mutex that clang's thread-safety analysis can follow (-Wthread-safety;
// https://clang.llvm.org/docs/ThreadSafetyAnalysis.html). libstdc++'s
// std::mutex carries no annotations, so the analysis cannot tell which lock
// a std::lock_guard holds; depot::Mutex and depot::MutexLock are the same
// operations with the annotations on. Under gcc the macros are empty and
// these are std::mutex and a lock guard.
//
// How a class states its locking:
//   Mutex mutex_;
//   std::deque<Job> queue_ DEPOT_GUARDED_BY(mutex_);     // read/written under it
//   void drain() DEPOT_REQUIRES(mutex_);                 // caller holds it
//   void submit(Job) DEPOT_EXCLUDES(mutex_);             // caller must not
// A clang build (tools/sanitize.sh thread builds with clang) then fails
// where a guarded member is touched, or a REQUIRES function called, without
// the lock held.
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>

#if defined(__clang__)
#define DEPOT_THREAD_ANNOTATION(x) __attribute__((x))
#else
#define DEPOT_THREAD_ANNOTATION(x)
#endif

#define DEPOT_CAPABILITY(name) DEPOT_THREAD_ANNOTATION(capability(name))
#define DEPOT_SCOPED_CAPABILITY DEPOT_THREAD_ANNOTATION(scoped_lockable)
#define DEPOT_GUARDED_BY(m) DEPOT_THREAD_ANNOTATION(guarded_by(m))
#define DEPOT_REQUIRES(...) DEPOT_THREAD_ANNOTATION(requires_capability(__VA_ARGS__))
#define DEPOT_EXCLUDES(...) DEPOT_THREAD_ANNOTATION(locks_excluded(__VA_ARGS__))
#define DEPOT_ACQUIRE(...) DEPOT_THREAD_ANNOTATION(acquire_capability(__VA_ARGS__))
#define DEPOT_RELEASE(...) DEPOT_THREAD_ANNOTATION(release_capability(__VA_ARGS__))
#define DEPOT_ASSERT_CAPABILITY(m) DEPOT_THREAD_ANNOTATION(assert_capability(m))
#define DEPOT_RETURN_CAPABILITY(m) DEPOT_THREAD_ANNOTATION(lock_returned(m))

namespace depot {

class DEPOT_CAPABILITY("mutex") Mutex {
 public:
  void lock() DEPOT_ACQUIRE() {
    mutex_.lock();
    owner_.store(std::this_thread::get_id(), std::memory_order_relaxed);
  }
  void unlock() DEPOT_RELEASE() {
    owner_.store(std::thread::id(), std::memory_order_relaxed);
    mutex_.unlock();
  }
  bool try_lock() DEPOT_THREAD_ANNOTATION(try_acquire_capability(true)) {
    if (!mutex_.try_lock()) return false;
    owner_.store(std::this_thread::get_id(), std::memory_order_relaxed);
    return true;
  }

  // Where the analysis cannot see that two names are one mutex (an object
  // holding a reference to the Map another holds too): aborts unless the
  // calling thread holds it, and tells the analysis that it does.
  void assert_held() const DEPOT_ASSERT_CAPABILITY(this) {
    if (owner_.load(std::memory_order_relaxed) != std::this_thread::get_id()) std::abort();
  }

  // Waits on `cv` with this mutex held (as std::condition_variable::wait:
  // released while waiting, held again on return; spurious wake-ups happen,
  // so callers wait in a loop on their condition).
  void wait(std::condition_variable& cv) DEPOT_REQUIRES(this) {
    std::unique_lock<std::mutex> held(mutex_, std::adopt_lock);
    owner_.store(std::thread::id(), std::memory_order_relaxed);
    cv.wait(held);
    owner_.store(std::this_thread::get_id(), std::memory_order_relaxed);
    held.release();  // still locked: the caller's MutexLock unlocks it
  }

 private:
  std::mutex mutex_;
  std::atomic<std::thread::id> owner_{};  // for assert_held only
};

// Holds a Mutex for its scope (std::lock_guard); unlock() ends the hold
// early.
class DEPOT_SCOPED_CAPABILITY MutexLock {
 public:
  explicit MutexLock(Mutex& mutex) DEPOT_ACQUIRE(mutex) : mutex_(mutex) { mutex_.lock(); }
  ~MutexLock() DEPOT_RELEASE() {
    if (held_) mutex_.unlock();
  }
  MutexLock(const MutexLock&) = delete;
  MutexLock& operator=(const MutexLock&) = delete;

  void unlock() DEPOT_RELEASE() {
    mutex_.unlock();
    held_ = false;
  }

 private:
  Mutex& mutex_;
  bool held_ = true;
};

}  // namespace depot
