#include "control/measure/measuring_messages.hpp"

#include <gtest/gtest.h>

#include <string>

namespace vmt::control::measure {
namespace {

// 6.1: the Q function numbers are fixed; the NC interprets no others.
TEST(MeasuringMessages, QFunctionNumbers) {
  EXPECT_EQ(kQ9992, 9992);
  EXPECT_EQ(kQ9998, 9998);
  EXPECT_EQ(kQ9999, 9999);
  EXPECT_EQ(QFunction(9992), nullptr);  // SETTING's: initialises the probe, no message
  EXPECT_EQ(QFunction(9997), nullptr);
  ASSERT_NE(QFunction(9998), nullptr);
  ASSERT_NE(QFunction(9999), nullptr);
}

// 6.1 Q9998: fault category 2, continued by a new advance program start. The probe program
// (control/plc/programs/probe_block.cpp) acts on these definitions.
TEST(MeasuringMessages, Q9998IsFaultCategory2) {
  const QFunctionDefinition& q = *QFunction(9998);
  EXPECT_EQ(q.number, 9998);
  EXPECT_EQ(q.fault_category, 2);
  EXPECT_STREQ(q.message_text, "CNC software fault message of TYPE 2");
  EXPECT_EQ(std::string(q.additional_text)
                .find("The fault has been triggered by programming "
                      "Q9998 in the NC program. The NC program was "
                      "stopped for safety reasons."),
            0u);
  EXPECT_NE(std::string(q.additional_text).find("continued after a new advance program start"),
            std::string::npos);
  EXPECT_TRUE(q.advance_continuable);
  EXPECT_EQ(q.plc_message, 204);  // 7.2 typical application, network 19
  for (const MeasuringMessage& m : {kOversize, kUndersize}) {
    EXPECT_EQ(m.q_function, 9998) << m.text;
    EXPECT_EQ(m.fault_category(), 2) << m.text;
    EXPECT_TRUE(m.advance_continuable()) << m.text;
  }
  EXPECT_STREQ(kOversize.text, "OVERSIZE");
  EXPECT_STREQ(kUndersize.text, "UNDERSIZE");
}

// 6.1 Q9999: fault category 1, the advance program stays inhibited: reverse program only.
TEST(MeasuringMessages, Q9999IsFaultCategory1) {
  const QFunctionDefinition& q = *QFunction(9999);
  EXPECT_EQ(q.number, 9999);
  EXPECT_EQ(q.fault_category, 1);
  EXPECT_STREQ(q.message_text, "CNC software fault message of TYPE 1");
  EXPECT_EQ(std::string(q.additional_text)
                .find("The fault has been triggered by programming "
                      "Q9999 in the NC program. For safety reasons, "
                      "the NC program can no longer be executed."),
            0u);
  EXPECT_NE(std::string(q.additional_text).find("after a reverse program has been triggered"),
            std::string::npos);
  EXPECT_FALSE(q.advance_continuable);
  EXPECT_EQ(q.plc_message, 205);  // 7.2 typical application, network 18
  for (const MeasuringMessage& m : {kTestPointNotFound, kProbeDisplacedOutsidePath,
                                    kIllegallyHighDimensionalDeviation, kCheckTool}) {
    EXPECT_EQ(m.q_function, 9999) << m.text;
    EXPECT_EQ(m.fault_category(), 1) << m.text;
    EXPECT_FALSE(m.advance_continuable()) << m.text;
  }
  EXPECT_STREQ(kTestPointNotFound.text, "TEST POINT NOT FOUND");
  // 6.1 names the probe displaced outside the measuring path beside the test point not found.
  EXPECT_EQ(std::string(kProbeDisplacedOutsidePath.text).find("TEST POINT NOT FOUND"), 0u);
  EXPECT_STREQ(kIllegallyHighDimensionalDeviation.text, "ILLEGALLY HIGH DIMENSIONAL DEVIATION");
  EXPECT_STREQ(kCheckTool.text, "CHECK TOOL");
}

}  // namespace
}  // namespace vmt::control::measure
