#pragma once
// Large arenas backed by 2 MiB pages where the kernel offers them (Linux THP in `madvise`
// mode). On the project's VMs each first touch of a fresh 4 KiB page costs ~11-20 us, a 2 MiB
// page about as much once its memory has been used before: a million-block program's arenas
// (a few hundred MiB) cost seconds in page faults otherwise.

#include <cstddef>
#include <cstdint>
#include <vector>

#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

namespace vmt::common {

/// Reserves room for `n` elements and advises the kernel to back the whole 2 MiB pages inside
/// it with huge pages. Reserving maps nothing: only what is written is paid for.
template <typename T>
void ReserveHugePages(std::vector<T>& v, size_t n) {
  v.reserve(n);
#ifdef MADV_HUGEPAGE
  constexpr uintptr_t kHuge = uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<uintptr_t>(v.data()) + kHuge - 1) & ~(kHuge - 1);
  const auto end = reinterpret_cast<uintptr_t>(v.data() + v.capacity()) & ~(kHuge - 1);
  // Advice only: where it is refused, 4 KiB pages serve as before.
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

}  // namespace vmt::common
