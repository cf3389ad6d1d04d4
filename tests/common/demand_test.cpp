#include "common/demand.hpp"

#include <gtest/gtest.h>

namespace vmt::common {
namespace {

int Checked(int v) {
  VMT_DEMAND(v >= 0, "Checked(%d): a count is never negative", v);
  return v;
}

TEST(Demand, HoldsQuietly) { EXPECT_EQ(Checked(3), 3); }

TEST(DemandDeathTest, NamesPlaceConditionAndMessage) {
  EXPECT_DEATH(Checked(-2),
               "internal error at .*demand_test.cpp:[0-9]+ \\(v >= 0\\): Checked\\(-2\\): a count is "
               "never negative");
}

TEST(Demand, EvaluatesItsMessageOnlyWhenBroken) {
  int calls = 0;
  auto count = [&calls] { return ++calls; };
  VMT_DEMAND(true, "%d", count());
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace vmt::common
