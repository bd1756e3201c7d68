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
namespace centaur::common {

/// Sets glibc's M_MMAP_THRESHOLD to 32 MiB and M_TRIM_THRESHOLD to 512 MiB (no-op elsewhere). Call once at the
/// start of main(), before other threads exist.
void retainFreedMemory();

}  // namespace centaur::common
