#pragma once
// Allocator for the engine's big arrays: large blocks are 2 MiB aligned and
// marked for transparent huge pages, so that scanning a neighbourhood of a
// million-disk system does not miss the TLB on every cell row.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>

namespace granular::detail {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

template <class T>
struct HugeAlloc {
  using value_type = T;
  HugeAlloc() = default;
  template <class U>
  HugeAlloc(const HugeAlloc<U>&) noexcept {}
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    const std::size_t align = bytes >= kHugePage ? kHugePage : (alignof(T) > 64 ? alignof(T) : 64);
    const std::size_t rounded = (bytes + align - 1) / align * align;
    void* ptr = std::aligned_alloc(align, rounded == 0 ? align : rounded);
    if (!ptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    if (bytes >= kHugePage) madvise(ptr, rounded, MADV_HUGEPAGE);  // a hint: failure is harmless
#endif
    return static_cast<T*>(ptr);
  }
  void deallocate(T* ptr, std::size_t) noexcept { std::free(ptr); }
  template <class U>
  bool operator==(const HugeAlloc<U>&) const noexcept { return true; }
};

}  // namespace granular::detail
