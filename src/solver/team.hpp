// The solver's thread team: a static split of index ranges and a spin
// barrier, used inside one OpenMP parallel region in place of work-shared
// loops and their implicit barriers.
//
// Why not `#pragma omp for` and `#pragma omp barrier`: libgomp's barrier
// enters the kernel (futex_wake) on every call, even with one thread, and
// on the KVM guests this project is measured on a system call costs about
// 0.5 us. Measured there (2026-12-01, tight loop of barriers): libgomp
// 1.2 us per barrier with 1 thread and 1.5 us with 2; this barrier 0.006 us
// and 0.31 us. A 2D sweep needs 12 barriers and takes 50-100 us on the
// shipped scenes, so the difference is 15-20% of the solve.
#pragma once

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace sablier {

// A counting barrier for `size` threads that spins in user space. After
// kSpinsBeforeYield pauses a waiting thread yields its core on every
// further check, so that a team larger than the machine (oversubscription)
// still progresses. Memory: everything a thread wrote before wait() is
// visible to every thread after it (release on arrival, acquire on leave).
class SpinBarrier {
 public:
  explicit SpinBarrier(int size = 1) : size_(size) {}
  // Only while no thread waits (e.g. by one thread before the others use it).
  void set_size(int size) { size_ = size; }

  void wait() {
    if (size_ <= 1) return;
    const unsigned gen = generation_.load(std::memory_order_relaxed);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == size_ - 1) {
      arrived_.store(0, std::memory_order_relaxed);
      generation_.store(gen + 1, std::memory_order_release);
      return;
    }
    int spins = 0;
    while (generation_.load(std::memory_order_acquire) == gen) {
      if (spins < kSpinsBeforeYield) {
        ++spins;
#if defined(__x86_64__) || defined(__i386__)
        _mm_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  }

 private:
  static constexpr int kSpinsBeforeYield = 1 << 14;
  int size_;
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) std::atomic<unsigned> generation_{0};
};

// The largest team whose threads may spin at a SpinBarrier: the run's
// thread count, but no more than the machine's processors. A thread more
// than there are cores waits for a descheduled one at every barrier: the
// 5 mm collapse with 3 threads on 2 cores took 88 s for 3 frames against
// 1.5 s on 2 threads.
inline int spinning_team_limit() {
  return std::max(1, std::min(omp_get_max_threads(), omp_get_num_procs()));
}

// One thread's view of the team: its rank, the team size and the shared
// barrier. split(n) gives the thread's contiguous share of [0, n), the same
// share for the same n on every call, so a thread that works on the same
// range in two loops reads back only its own writes and needs no barrier
// between them.
struct Team {
  int rank = 0;
  int size = 1;
  SpinBarrier* barrier = nullptr;

  template <class I>
  std::pair<I, I> split(I begin, I end) const {
    const I n = end - begin;
    const I q = n / size, r = n % size;
    const I lo = begin + rank * q + (rank < r ? rank : r);
    return {lo, lo + q + (rank < r ? 1 : 0)};
  }
  template <class I>
  std::pair<I, I> split(I n) const {
    return split<I>(I(0), n);
  }
  void sync() const {
    if (barrier) barrier->wait();
  }
};

}  // namespace sablier
