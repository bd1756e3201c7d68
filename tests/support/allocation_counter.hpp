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

#if defined(__SANITIZE_ADDRESS__)
#define CENTAUR_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CENTAUR_TEST_ASAN 1
#endif
#endif

#ifdef CENTAUR_TEST_ASAN
// Under AddressSanitizer the allocator is ASan's (interposing malloc would hand its blocks to glibc): every
// allocation, malloc and operator new alike, is counted by the sanitizer's own allocation hook instead.
// (declared here as in <sanitizer/allocator_interface.h>, which g++ does not install)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*, std::size_t),
                                                         void (*free_hook)(const volatile void*));

namespace centaur_test {
inline void countAllocation(const volatile void*, std::size_t) {
  g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
}
inline void ignoreFree(const volatile void*) {}
inline const bool g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(countAllocation, ignoreFree) != 0;
}  // namespace centaur_test

#else
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
#endif  // CENTAUR_TEST_ASAN
