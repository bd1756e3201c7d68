#pragma once
// Counts every heap allocation of a test binary: a replaced global operator new (C++ allocations) and malloc &
// friends interposed on glibc's (Eigen allocates with malloc, not operator new). The replacements are ordinary
// (non-inline) definitions, as the language requires: include this header in exactly ONE source file of a test
// binary (every centaur test binary is a single source file).
//
//   const long before = centaur_test::heapAllocations();
//   ... code that must not allocate ...
//   EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace centaur_test {
inline std::atomic<long> g_new_calls{0};
inline std::atomic<long> g_malloc_calls{0};
/// operator new calls + malloc/calloc/realloc/memalign calls so far.
inline long heapAllocations() { return g_new_calls.load() + g_malloc_calls.load(); }
}  // namespace centaur_test

// ---- malloc interposition (glibc exports the real implementations as __libc_*; its declarations are
//      noexcept in C++, so are these definitions) ----
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t size) noexcept {
  centaur_test::g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  centaur_test::g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  centaur_test::g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  centaur_test::g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept { return memalign(alignment, size); }
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  *out = memalign(alignment, size);
  return *out ? 0 : 12;  // ENOMEM
}
void free(void* p) noexcept { __libc_free(p); }
}

// ---- counting global operator new ----
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  centaur_test::g_new_calls.fetch_add(1, std::memory_order_relaxed);
  if (void* p = __libc_malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  centaur_test::g_new_calls.fetch_add(1, std::memory_order_relaxed);
  if (void* p = __libc_malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }
#pragma GCC diagnostic pop
