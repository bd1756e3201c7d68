#pragma once
// Keep freed heap memory in the process instead of returning it to the kernel.
//
// glibc gives the free top of a heap back to the kernel once 128 KB of it are free, and serves allocations of
// 128 KB and more with fresh mappings; every page of such memory faults in again when it is next used. The
// planner builds its workspaces anew for every solve (megabytes of KKT stage blocks, derivative buffers on both
// threads), so a process that solves repeatedly (`bench planner`, sweeps, warm re-plans) spends a large part of
// its time in page faults: on this project's 2-vCPU VM, 86 000 faults and 4.1 s for 25 warm re-plans of the squat
// jump against 8 000 faults and 3.0 s with the memory kept (docs/benchmarks.md). The process keeps at most its
// peak heap; the 1 kHz control loop does not allocate at all.
#include <cstddef>

namespace centaur::common {

/// Sets glibc's M_MMAP_THRESHOLD to 32 MiB and M_TRIM_THRESHOLD to 512 MiB (no-op elsewhere). Call once at the
/// start of main(), before other threads exist.
void retainFreedMemory();

/// Lets every thread allocate from the main heap (glibc's M_ARENA_MAX = 1; no-op elsewhere) instead of giving each
/// thread a heap of its own. A thread's own heap starts as fresh pages, so the planner's second core faulted in all
/// of the stage blocks it fills during the first KKT factorization of a process (16-44 ms, 2 ms later); from the
/// main heap they reuse memory the setup has already touched and freed. For a command whose threads allocate
/// little once started (a plan); call before those threads exist.
void shareOneHeap();

/// Asks the kernel to back the next `bytes` of the main heap with transparent huge pages (2 MiB; madvise
/// MADV_HUGEPAGE on a block taken from the heap and freed again), which is what glibc's `glibc.malloc.hugetlb=1`
/// tunable does for every heap extension but a program cannot switch on for itself once started. A fresh
/// `centaur plan` process otherwise faults the planner's workspaces in 4 KiB at a time (~4 000 minor page faults).
/// Call after retainFreedMemory(), so that the block comes from the heap and stays in it; `bytes` is clamped to
/// 30 MiB, below its mmap threshold. Returns whether the kernel accepted the advice (false where transparent huge
/// pages are not built in, and off glibc); where the system's THP mode is `never` it is accepted and changes nothing.
bool hugePagesForHeap(std::size_t bytes);

}  // namespace centaur::common
