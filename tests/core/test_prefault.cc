// core/prefault.h: faulting pages in ahead of writes changes no contents, whether the pages are
// already there (heap reused) or fresh, at any alignment and size; small arrays are left alone.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdint>
#include <vector>

#include "core/prefault.h"
#include "core/table.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRDFIT_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define BRDFIT_TEST_ASAN 1
#endif

namespace brdfit {
namespace {

TEST(Prefault, ContentsOfWrittenPagesAreKept) {
  std::vector<double> v(1 << 20);  // 8 MB
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<double>(i) * 0.5 - 7.0;
  // Unaligned start and end inside the array, and the whole array.
  PrefaultForWrite(reinterpret_cast<const char*>(v.data()) + 13, v.size() * sizeof(double) - 29);
  PrefaultForWrite(v.data(), v.size() * sizeof(double));
  for (std::size_t i = 0; i < v.size(); ++i) {
    ASSERT_EQ(v[i], static_cast<double>(i) * 0.5 - 7.0) << i;
  }
}

long MinorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// A fresh array prefaulted, then written: (nearly) no page faults at the writes, on kernels that
// have MADV_POPULATE_WRITE (5.14+); elsewhere the writes fault as before and the test says so.
TEST(Prefault, FreshArrayIsWrittenWithoutPageFaults) {
#if defined(BRDFIT_TEST_ASAN)
  GTEST_SKIP() << "under AddressSanitizer the writes fault in shadow memory";
#endif
  constexpr std::size_t n = std::size_t{4} << 20;  // 32 MB of doubles: a fresh mapping
  std::vector<double> v;
  v.reserve(n);
  PrefaultForWrite(v.data(), n * sizeof(double));
  const long before = MinorFaults();
  v.assign(n, 1.5);
  const long faults = MinorFaults() - before;
  if (faults > 1000) GTEST_SKIP() << faults << " faults: this kernel does not populate ahead";
  EXPECT_LT(faults, 64);
  EXPECT_EQ(v[n - 1], 1.5);
}

TEST(Prefault, SmallAndNullArraysAreLeftAlone) {
  std::vector<std::uint8_t> small(4096, 9);
  PrefaultForWrite(small.data(), small.size());
  PrefaultForWrite(nullptr, std::size_t{1} << 30);
  EXPECT_EQ(small[4095], 9);
}

// Table::Empty (prefaulted) is still all-invalid and all zero.
TEST(Prefault, EmptyTableIsZeroAndInvalid) {
  const Table t = Table::Empty(Grid::Merl());
  ASSERT_EQ(t.rgb.size(), 3 * Grid::Merl().NumCells());
  for (const double v : t.rgb) ASSERT_EQ(v, 0.0);
  for (const std::uint8_t f : t.valid) ASSERT_EQ(f, 0);
}

}  // namespace
}  // namespace brdfit
