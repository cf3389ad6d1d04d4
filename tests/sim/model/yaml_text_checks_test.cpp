// Scene and machine text: UTF-8, keys that are names given once, YAML errors with a reason,
// and numbers read in their range - each fault placed at file:line:col with its YAML path.

#include "sim/model/yaml_text_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim/model/model_error.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlTextChecks, Utf8IsAcceptedAndAnythingElsePlaced) {
  EXPECT_EQ(ErrorOf([] { CheckUtf8Text("s.yaml", "scene: caf\xC3\xA9 \xE2\x82\xAC\n"); }), "");
  EXPECT_EQ(ErrorOf([] { CheckUtf8Text("s.yaml", "\xEF\xBB\xBFscene: x\n"); }), "");
  EXPECT_EQ(ErrorOf([] { CheckUtf8Text("s.yaml", "a: 1\nscene: caf\xE9\n"); }),
            "s.yaml:2:11: not UTF-8 text (byte 0xE9); save the file as UTF-8");
  // Overlong forms, surrogates and a sequence cut by the end are no UTF-8 either.
  for (const char* bad : {"\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "x\xE2\x82"})
    EXPECT_THAT(ErrorOf([&] { CheckUtf8Text("s.yaml", bad); }), HasSubstr("not UTF-8")) << bad;
}

TEST(YamlTextChecks, KeysAreNamesGivenOnce) {
  const auto check = [](const std::string& text) {
    return ErrorOf([&] { CheckMapKeys("s.yaml", YAML::Load(text)); });
  };
  EXPECT_EQ(check("a: 1\nb: {c: 2, d: [1, {e: 3}]}\n"), "");
  EXPECT_EQ(check("a: 1\nb: {c: 2, c: 3}\n"),
            "s.yaml:2:11: b.c: duplicate key 'c' (first given at line 2:5)");
  EXPECT_EQ(check("l:\n  - {x: 1}\n  - {x: 1, x: 2}\n"),
            "s.yaml:3:12: l[1].x: duplicate key 'x' (first given at line 3:6)");
  EXPECT_EQ(check("[a, b]: 1\n"), "s.yaml:1:1: (top level): a key must be a name, not a list");
  EXPECT_EQ(check("a: {~: 1}\n"), "s.yaml:1:5: a: a key must be a name, not null");
  EXPECT_THAT(check("a: {{b: 1}: 2}\n"), HasSubstr("a key must be a name, not a map"));
  // Aliases of one anchor are walked once: nested ones cannot make the walk exponential.
  std::string laughs = "a0: &a0 {k: 1}\n";
  for (int i = 1; i < 40; ++i)
    laughs += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [*a" +
              std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + "]\n";
  EXPECT_EQ(check(laughs), "");
}

TEST(YamlTextChecks, SyntaxErrorsGiveAPlaceAndAReason) {
  try {
    YAML::Load("a: [1, 2\n");
    FAIL();
  } catch (const YAML::Exception& e) {
    EXPECT_THAT(YamlSyntaxError("s.yaml", e),
                HasSubstr("s.yaml:2:1: YAML syntax error: a '[' is not closed by ']'"));
  }
}

TEST(YamlRangedRead, NumbersOutsideTheirRangeNameIt) {
  const YamlNode root(YAML::Load("a: 1e308\nb: -1\nc: 5\nd: 1.5\ne: 7\n"), "s.yaml", "");
  EXPECT_EQ(ErrorOf([&] { root["a"].Double(); }),
            "s.yaml:1:4: a: must be in -1000000000..1000000000, got 1e308");
  EXPECT_EQ(ErrorOf([&] { root["b"].Double(0, 86400); }),
            "s.yaml:2:4: b: must be in 0..86400, got -1");
  EXPECT_DOUBLE_EQ(root["c"].Double(0, 5), 5);
  EXPECT_DOUBLE_EQ(root.Double("missing", -1, 0, 10), -1);  // a fallback is no input
  EXPECT_EQ(ErrorOf([&] { root.Double("c", 0, 0, 2); }), "s.yaml:3:4: c: must be in 0..2, got 5");
  EXPECT_EQ(ErrorOf([&] { root["d"].Int(0, 9); }),
            "s.yaml:4:4: d: expected a whole number in 0..9, got \"1.5\"");
  EXPECT_EQ(ErrorOf([&] { root["e"].Int(0, 6); }), "s.yaml:5:4: e: must be in 0..6, got 7");
}

TEST(YamlRangedRead, AKeyIsPlacedAtItself) {
  const YamlNode root(YAML::Load("initial:\n  Z: 1\n  Q: 2\n"), "s.yaml", "");
  EXPECT_THROW(root["initial"].KeyNode("Q").Fail("no axis 'Q'"), ModelError);
  EXPECT_EQ(ErrorOf([&] { root["initial"].KeyNode("Q").Fail("no axis 'Q'"); }),
            "s.yaml:3:3: initial.Q: no axis 'Q'");
}

}  // namespace
}  // namespace vmt::sim
