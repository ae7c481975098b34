#include "core/prefault.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace brdfit {

void PrefaultForWrite(const void* p, std::size_t bytes) {
#if defined(__linux__)
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14 uapi; older headers lack it, older kernels refuse it
#endif
  if (bytes < (std::size_t{1} << 20) || p == nullptr) return;
  static const std::uintptr_t page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  // Whole pages around the array: the neighbouring bytes of its first and last pages belong to
  // the same mapping (the allocator's), and populating does not change any page's contents.
  const auto begin = reinterpret_cast<std::uintptr_t>(p) & ~(page - 1);
  const auto end = reinterpret_cast<std::uintptr_t>(p) + bytes;
  // Transparent huge pages where the kernel offers them on request (its "madvise" mode): a
  // 35 MB table is then ~18 faults of 2 MB instead of ~8,500 of 4 KB. Advice only: refused or
  // unavailable, the pages stay small.
  (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  // Failure (EINVAL on kernels before 5.14, ENOMEM) leaves the pages to be faulted in on write.
  (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace brdfit
