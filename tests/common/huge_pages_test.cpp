#include "common/huge_pages.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace vmt::common {
namespace {

TEST(HugePages, ReservesWithoutFilling) {
  std::vector<double> v;
  ReserveHugePages(v, size_t{1} << 20);  // 8 MiB: several whole 2 MiB pages inside
  EXPECT_GE(v.capacity(), size_t{1} << 20);
  EXPECT_TRUE(v.empty());
  v.assign(1000, 1.5);  // the advised memory is ordinary memory
  EXPECT_EQ(v[999], 1.5);
}

}  // namespace
}  // namespace vmt::common
