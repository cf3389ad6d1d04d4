// Tool nose radius compensation (G40/G41/G42, G18): seeded random contours checked against
// independent invariants (the nose centre at r from its element, continuity, no backwards
// motion, no gouge of the neighbouring elements) and, for polylines, against a closed-form
// reference.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// Seeded random contours.

// Closed-form reference for a polyline under G41/G42: at a vertex turning by theta towards the
// tool (inner), both offset lines are cut back by r * tan(|theta| / 2); at an outer vertex a
// transition arc around the vertex joins the perpendicular offsets. A block is too short
// (gouge) when its cut-backs add up to more than its length.
struct PolylineCase {
  std::vector<ContourElement> in;
  std::vector<ContourElement> expected;  ///< the full tip path as if nothing were too short
  int64_t first_too_short = -1;          ///< tag, -1 if none
  double min_slack = 1e9;                ///< smallest length - cut-backs
};

PolylineCase RandomPolyline(std::mt19937_64& rng, int blocks, double min_length, double max_length,
                            double max_turn_deg, double max_r) {
  std::uniform_real_distribution<double> unit(0, 1);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  PolylineCase c;
  const Side side = unit(rng) < 0.5 ? Side::kLeft : Side::kRight;
  const double s = side == Side::kLeft ? 1 : -1;
  const double r = uniform(0.05, max_r);
  const int edge = static_cast<int>(rng() % 10);
  const Vec2 tip = TipFromCentre(edge, r);
  // Vertices and directions of the compensated blocks.
  std::vector<Vec2> v{{uniform(-50, 50), uniform(-50, 50)}};
  std::vector<Vec2> d;
  double angle = uniform(-kPi, kPi);
  for (int i = 0; i < blocks; ++i) {
    if (i > 0) {
      const double turn = uniform(2, max_turn_deg) * kPi / 180;
      angle += unit(rng) < 0.5 ? turn : -turn;
    }
    d.push_back({std::cos(angle), std::sin(angle)});
    v.push_back(v.back() + uniform(min_length, max_length) * d.back());
  }
  auto block = [&](Vec2 a, Vec2 b, Side sd) {
    ContourElement e;
    e.start = a;
    e.end = b;
    e.side = sd;
    e.nose_radius_mm = r;
    e.edge_position = edge;
    e.tag = static_cast<int64_t>(c.in.size());
    return e;
  };
  const Vec2 from = v[0] + Vec2{uniform(-10, 10), uniform(-10, 10)};
  const Vec2 to = v.back() + Vec2{uniform(-10, 10), uniform(-10, 10)};
  c.in.push_back(block(from, v[0], side));  // start-up
  for (int i = 0; i < blocks; ++i) c.in.push_back(block(v[i], v[i + 1], side));
  c.in.push_back(block(v.back(), to, Side::kOff));  // cancel
  // Reference.
  std::vector<double> cut(blocks + 1, 0.0);  // at vertex i, between blocks i-1 and i
  std::vector<bool> inner(blocks + 1, false);
  for (int i = 1; i < blocks; ++i) {
    const double theta = std::atan2(Cross(d[i - 1], d[i]), Dot(d[i - 1], d[i]));
    inner[i] = s * theta > 0;
    if (inner[i]) cut[i] = r * std::tan(std::abs(theta) / 2);
  }
  auto normal = [&](int i) { return s * LeftOf(d[i]); };
  ContourElement e = c.in[0];
  e.end = v[0] + r * normal(0) + tip;
  c.expected.push_back(e);
  for (int i = 0; i < blocks; ++i) {
    const double length = Norm(v[i + 1] - v[i]);
    const double slack = length - cut[i] - cut[i + 1];
    c.min_slack = std::min(c.min_slack, std::abs(slack));
    if (slack < 0 && c.first_too_short < 0) c.first_too_short = c.in[i + 1].tag;
    e = c.in[i + 1];
    e.start = v[i] + r * normal(i) + cut[i] * d[i] + tip;
    e.end = v[i + 1] + r * normal(i) - cut[i + 1] * d[i] + tip;
    c.expected.push_back(e);
    if (i + 1 < blocks && !inner[i + 1]) {
      ContourElement arc = c.in[i + 2];
      arc.inserted = true;
      arc.kind = s > 0 ? Kind::kArcCw : Kind::kArcCcw;
      arc.centre = v[i + 1] + tip;
      arc.start = v[i + 1] + r * normal(i) + tip;
      arc.end = v[i + 1] + r * normal(i + 1) + tip;
      c.expected.push_back(arc);
    }
  }
  e = c.in.back();
  e.start = v.back() + r * normal(blocks - 1) + tip;
  c.expected.push_back(e);
  return c;
}

::testing::AssertionResult SameElements(const std::vector<ContourElement>& actual,
                                        const std::vector<ContourElement>& expected, size_t count) {
  if (actual.size() != count)
    return ::testing::AssertionFailure() << actual.size() << " elements, expected " << count;
  for (size_t i = 0; i < count; ++i) {
    const ContourElement &a = actual[i], &b = expected[i];
    if (a.kind != b.kind || a.tag != b.tag || a.inserted != b.inserted ||
        !Near(a.start, b.start, 1e-8) || !Near(a.end, b.end, 1e-8) ||
        (a.kind != Kind::kLine && !Near(a.centre, b.centre, 1e-8)))
      return ::testing::AssertionFailure() << "element " << i << " differs from the reference";
  }
  return ::testing::AssertionSuccess();
}

void CheckRandomPolylines(uint64_t seed, int cases, int blocks, double min_length,
                          double max_length, double max_turn_deg, double max_r, int& errors,
                          int& successes) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < cases; ++k) {
    const PolylineCase c = RandomPolyline(rng, blocks, min_length, max_length, max_turn_deg, max_r);
    if (c.min_slack < 1e-6) continue;  // too close to the limit to call
    const Result run = Compensate(c.in);
    if (c.first_too_short >= 0) {
      ++errors;
      EXPECT_TRUE(run.error) << "case " << k;
      if (run.error) {
        EXPECT_EQ(run.error->tag, c.first_too_short) << "case " << k;
        EXPECT_THAT(run.error->message, HasSubstr("too short for the tool nose radius"));
      }
      // Everything before the too-short block came out as the reference has it.
      size_t prefix = 0;
      while (prefix < c.expected.size() &&
             !(c.expected[prefix].tag == c.first_too_short && !c.expected[prefix].inserted))
        ++prefix;
      EXPECT_TRUE(SameElements(run.out, c.expected, prefix)) << "case " << k;
    } else {
      ++successes;
      EXPECT_FALSE(run.error) << "case " << k << ": " << run.error->message;
      EXPECT_TRUE(SameElements(run.out, c.expected, c.expected.size())) << "case " << k;
      EXPECT_TRUE(CheckPath(c.in, run.out, true)) << "case " << k;
    }
    if (::testing::Test::HasFailure()) {
      std::cout << "seed " << seed << " case " << k << "\ninput:\n"
                << Csv(c.in) << "output:\n"
                << Csv(run.out) << "reference:\n"
                << Csv(c.expected);
      return;
    }
  }
}

TEST(ToolRadiusCompensationTest, RandomPolylinesWithoutGougesMatchTheReference) {
  int errors = 0, successes = 0;
  // Blocks long enough for any cut-back: tan(60 deg) * 1 * 2 < 4.
  CheckRandomPolylines(20240601, 300, 60, 4, 20, 120, 1.0, errors, successes);
  EXPECT_EQ(errors, 0);
  EXPECT_GE(successes, 290);
}

TEST(ToolRadiusCompensationTest, RandomPolylinesWithGougesMatchTheReference) {
  int errors = 0, successes = 0;
  CheckRandomPolylines(7, 1000, 12, 0.05, 10, 178, 2.0, errors, successes);
  std::cout << "random polylines: " << successes << " compensated, " << errors << " too short\n";
  // Both outcomes occur often enough to mean something.
  EXPECT_GE(errors, 50);
  EXPECT_GE(successes, 20);
  // Three-block polylines with sharp turns: the first and the last block of a chain too.
  int short_errors = 0, short_successes = 0;
  std::mt19937_64 rng(99);
  for (int k = 0; k < 2000 && !::testing::Test::HasFailure(); ++k) {
    const PolylineCase c = RandomPolyline(rng, 3, 0.05, 6, 178, 1.5);
    if (c.min_slack < 1e-6) continue;
    const Result run = Compensate(c.in);
    if (c.first_too_short >= 0) {
      ++short_errors;
      ASSERT_TRUE(run.error) << "case " << k << "\n" << Csv(c.in);
      EXPECT_EQ(run.error->tag, c.first_too_short) << "case " << k << "\n" << Csv(c.in);
    } else {
      ++short_successes;
      ASSERT_FALSE(run.error) << "case " << k << ": " << run.error->message << "\n" << Csv(c.in);
      EXPECT_TRUE(SameElements(run.out, c.expected, c.expected.size()))
          << "case " << k << "\n"
          << Csv(c.in) << Csv(run.out) << Csv(c.expected);
      EXPECT_TRUE(CheckPath(c.in, run.out, true)) << "case " << k << "\n" << Csv(run.out);
    }
  }
  EXPECT_GE(short_errors, 100);
  EXPECT_GE(short_successes, 100);
}

// Random contours of lines and arcs, tangent and not, under one side, radius and edge
// position: the invariants must hold whenever no error is reported, and the errors must be the
// documented ones. `lathe_profile` makes outside-turning profiles (X a function of Z, the tool
// on the +X side, moving -Z under G42 or +Z under G41), on which the material is consistently
// on one side, so that the nose must also keep r from the neighbouring blocks; the general
// contours may curl back over their neighbours (which one element of look-ahead cannot see),
// so there only the block's own distance is checked.
struct RandomStats {
  int successes = 0, radius_errors = 0, gouges = 0, inserted = 0, arcs = 0;
  int too_short = 0, no_intersection = 0, crossing = 0;  ///< the gouges by kind
};

// Signed distance of a point from the whole offset curve (line or circle) of a compensated
// block: the nose-centre curve extended beyond the block's ends.
double FromOffsetCurve(Vec2 x, const ContourElement& e) {
  const double s = e.side == Side::kLeft ? 1 : -1;
  if (e.kind == Kind::kLine) {
    const Vec2 n = s * LeftOf(UnitOf(e.end - e.start));
    return Dot(x - e.start, n) - e.nose_radius_mm;
  }
  const double sigma = e.kind == Kind::kArcCcw ? 1 : -1;
  return Norm(x - e.centre) - (Norm(e.start - e.centre) - sigma * s * e.nose_radius_mm);
}

// Independent check of a "no intersection" error at the corner before block `tag`: the
// corner turns towards the tool (inner) and the offset curves of the two blocks, sampled, do
// not cross (at least one of them is a circle at such a corner).
::testing::AssertionResult OffsetsDoNotMeet(const std::vector<ContourElement>& in, int64_t tag) {
  const ContourElement& b = in.at(tag);
  const ContourElement& a = in.at(tag - 1);
  auto tangent = [](const ContourElement& e, Vec2 p) {
    if (e.kind == Kind::kLine) return UnitOf(e.end - e.start);
    return (e.kind == Kind::kArcCcw ? 1.0 : -1.0) * LeftOf(UnitOf(p - e.centre));
  };
  const Vec2 ta = tangent(a, a.end), tb = tangent(b, b.start);
  const double s = b.side == Side::kLeft ? 1 : -1;
  if (s * std::atan2(Cross(ta, tb), Dot(ta, tb)) <= 0)
    return ::testing::AssertionFailure() << "not an inner corner";
  const ContourElement& circle = b.kind != Kind::kLine ? b : a;
  const ContourElement& other = b.kind != Kind::kLine ? a : b;
  if (circle.kind == Kind::kLine) return ::testing::AssertionFailure() << "two lines";
  const double sigma = circle.kind == Kind::kArcCcw ? 1 : -1;
  const double radius = Norm(circle.start - circle.centre) -
                        sigma * (circle.side == Side::kLeft ? 1 : -1) * circle.nose_radius_mm;
  int sign = 0;
  for (int i = 0; i < 3600; ++i) {
    const double angle = 2 * kPi * i / 3600;
    const Vec2 x = circle.centre + radius * Vec2{std::cos(angle), std::sin(angle)};
    const double d = FromOffsetCurve(x, other);
    if (std::abs(d) < 1e-6) continue;
    const int here = d > 0 ? 1 : -1;
    if (sign != 0 && here != sign)
      return ::testing::AssertionFailure() << "the offset curves cross near " << Str(x);
    sign = here;
  }
  return ::testing::AssertionSuccess();
}

RandomStats RunRandomContours(uint64_t seed, int cases, bool lathe_profile) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  RandomStats stats;
  for (int k = 0; k < cases && !::testing::Test::HasFailure(); ++k) {
    const int blocks = 2 + static_cast<int>(rng() % 12);
    Program p;
    p.side = unit(rng) < 0.5 ? Side::kLeft : Side::kRight;
    p.r = uniform(0.1, 1.5);
    p.edge = static_cast<int>(rng() % 10);
    // Headings allowed: all, or those that keep X a function of Z with the tool at +X.
    const double low = p.side == Side::kRight ? kPi / 2 : -kPi / 2;
    const double high = low + kPi;
    Vec2 at{uniform(-20, 20), uniform(-20, 20)};
    double heading = lathe_profile ? uniform(low, high) : uniform(-kPi, kPi);
    p.From(at.z + uniform(-5, 5), at.x + uniform(-5, 5)).Line(at.z, at.x);  // start-up
    for (int i = 0; i < blocks; ++i) {
      if (unit(rng) < 0.5) {
        if (lathe_profile) {
          heading = uniform(low, high);
        } else {
          const double turn = uniform(5, 170) * kPi / 180;
          heading += unit(rng) < 0.5 ? turn : -turn;
        }
      }
      const Vec2 t{std::cos(heading), std::sin(heading)};
      const double sigma = unit(rng) < 0.5 ? 1 : -1;
      double max_sweep = 170 * kPi / 180;
      if (lathe_profile)
        max_sweep = std::min(max_sweep, sigma > 0 ? high - heading : heading - low);
      if (unit(rng) < 0.5 || max_sweep < 5 * kPi / 180) {
        at = at + uniform(0.2, 15) * t;
        p.Line(at.z, at.x);
      } else {
        const double radius = uniform(0.2, 12);
        const Vec2 c = at + (sigma * radius) * LeftOf(t);
        const double sweep = uniform(5 * kPi / 180, max_sweep);
        at = c + Rotate(at - c, sigma * sweep);
        heading += sigma * sweep;
        if (sigma > 0)
          p.Ccw(at.z, at.x, c.z, c.x);
        else
          p.Cw(at.z, at.x, c.z, c.x);
        ++stats.arcs;
      }
    }
    p.G40().Line(at.z + uniform(-5, 5), at.x + uniform(-5, 5));
    const Result run = Compensate(p.blocks);
    if (run.error) {
      const std::string& m = run.error->message;
      if (m.find("smaller than the tool nose radius") != std::string::npos) {
        ++stats.radius_errors;
        const ContourElement& b = p.blocks.at(run.error->tag);
        EXPECT_NE(b.kind, Kind::kLine) << "case " << k;
        const double sigma = b.kind == Kind::kArcCcw ? 1 : -1;
        const double s = b.side == Side::kLeft ? 1 : -1;
        EXPECT_LT(Norm(b.start - b.centre) - sigma * s * b.nose_radius_mm, 0) << "case " << k;
      } else {
        ++stats.gouges;
        EXPECT_THAT(m, HasSubstr("contour violation (gouge)")) << "case " << k;
        if (m.find("too short") != std::string::npos) ++stats.too_short;
        if (m.find("no intersection") != std::string::npos) {
          ++stats.no_intersection;
          EXPECT_TRUE(OffsetsDoNotMeet(p.blocks, run.error->tag)) << "case " << k;
        }
        if (m.find("crosses") != std::string::npos) ++stats.crossing;
      }
      continue;
    }
    ++stats.successes;
    stats.inserted += static_cast<int>(Inserted(run.out).size());
    EXPECT_TRUE(CheckPath(p.blocks, run.out, lathe_profile))
        << "seed " << seed << " case " << k << "\ninput:\n"
        << Csv(p.blocks) << "output:\n"
        << Csv(run.out);
  }
  std::cout << "random " << (lathe_profile ? "lathe profiles" : "contours") << ": "
            << stats.successes << " compensated, " << stats.radius_errors << " radius errors, "
            << stats.gouges << " gouges (" << stats.too_short << " too short, "
            << stats.no_intersection << " no intersection, " << stats.crossing << " crossing), "
            << stats.inserted << " inserted elements, " << stats.arcs << " arcs\n";
  return stats;
}

TEST(ToolRadiusCompensationTest, RandomContoursWithArcsKeepTheInvariants) {
  const RandomStats stats = RunRandomContours(424242, 3000, false);
  EXPECT_GE(stats.successes, 300);
  EXPECT_GE(stats.radius_errors, 20);
  EXPECT_GE(stats.gouges, 20);
  EXPECT_GE(stats.inserted, 200);
}

TEST(ToolRadiusCompensationTest, RandomLatheProfilesDoNotGougeTheirNeighbours) {
  const RandomStats stats = RunRandomContours(1357, 3000, true);
  EXPECT_GE(stats.successes, 300);
  EXPECT_GE(stats.radius_errors, 20);
  EXPECT_GE(stats.gouges, 20);
  EXPECT_GE(stats.inserted, 200);
}

}  // namespace
}  // namespace vmt::control::channel
