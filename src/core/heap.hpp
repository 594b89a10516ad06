// How the programs (the command-line tool, the benchmarks) ask glibc to
// keep freed memory: one setting, so that the benchmarks time the steps as
// the tool runs them.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sablier {

// Every frame builds its files (hundreds of kB to MBs) in fresh buffers, and
// every step its sorted particle arrays and solver buffers. glibc serves
// blocks that large with mmap and unmaps them on free, so each frame and
// step page-faulted them in again; keeping them in the heap lets the next
// reuse the pages. Measured on collapse2d (1 s, 30 frames, one thread):
// 0.45 s outside the steps before, 0.24 s after (with the checkpoint buffer
// sized up front); system time 0.22 s against 0.07.
inline void keep_freed_memory_in_heap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace sablier
