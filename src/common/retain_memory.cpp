#include "common/retain_memory.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#endif

namespace centaur::common {

void retainFreedMemory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: half of a thread arena's 64 MiB heap
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

void shareOneHeap() {
#if defined(__GLIBC__)
  mallopt(M_ARENA_MAX, 1);
#endif
}

bool hugePagesForHeap(std::size_t bytes) {
#if defined(__GLIBC__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  bytes = std::min<std::size_t>(bytes, std::size_t{30} << 20);
  char* block = static_cast<char*>(std::malloc(bytes));
  if (block == nullptr) return false;
  // Only whole 2 MiB pages inside the block: the advice must not reach memory the heap does not own.
  const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(block) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t hi = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kHuge - 1);
  const bool ok = hi > lo && madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE) == 0;
  std::free(block);
  return ok;
#else
  (void)bytes;
  return false;
#endif
}

}  // namespace centaur::common
