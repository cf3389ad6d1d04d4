// Tool nose radius compensation (G40/G41/G42, G18): exact paths of hand-computed lathe contours,
// start-up, cancel, side change, errors, and seeded random contours checked against independent
// invariants (the nose centre at r from its element, continuity, no backwards motion, no gouge
// of the neighbouring elements) and, for polylines, against a closed-form reference.

#include "control/channel/tool_radius_compensation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace vmt::control::channel {
namespace {

using ::testing::HasSubstr;
using Side = CompensationSide;
using Kind = ElementKind;

constexpr double kTol = 1e-9;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Building programs and running them.

// A contour program: modal side, radius, edge position and rapid, like the NC blocks that make
// them; tags are the block indices.
struct Program {
  Side side = Side::kOff;
  double r = 0.8;
  int edge = 3;
  bool rapid = false;
  Vec2 at;
  std::vector<ContourElement> blocks;

  Program& From(double z, double x) {
    at = {z, x};
    return *this;
  }
  ContourElement Block(Kind kind, Vec2 end, Vec2 centre) const {
    ContourElement e;
    e.kind = kind;
    e.start = at;
    e.end = end;
    e.centre = centre;
    e.side = side;
    e.nose_radius_mm = r;
    e.edge_position = edge;
    e.tag = static_cast<int64_t>(blocks.size());
    e.rapid = rapid;
    return e;
  }
  Program& Line(double z, double x) {
    blocks.push_back(Block(Kind::kLine, {z, x}, {}));
    at = {z, x};
    return *this;
  }
  Program& Cw(double z, double x, double cz, double cx) {
    blocks.push_back(Block(Kind::kArcCw, {z, x}, {cz, cx}));
    at = {z, x};
    return *this;
  }
  Program& Ccw(double z, double x, double cz, double cx) {
    blocks.push_back(Block(Kind::kArcCcw, {z, x}, {cz, cx}));
    at = {z, x};
    return *this;
  }
  Program& G40() {
    side = Side::kOff;
    return *this;
  }
  Program& G41() {
    side = Side::kLeft;
    return *this;
  }
  Program& G42() {
    side = Side::kRight;
    return *this;
  }
};

struct Result {
  std::vector<ContourElement> out;
  std::optional<CompensationError> error;
};

Result Compensate(const std::vector<ContourElement>& in, bool flush = true) {
  ToolRadiusCompensation trc;
  Result result;
  ContourElement e;
  for (const ContourElement& b : in) {
    trc.Push(b);
    while (trc.Pop(e)) result.out.push_back(e);
  }
  if (flush) trc.Flush();
  while (trc.Pop(e)) result.out.push_back(e);
  result.error = trc.error();
  return result;
}

// Non-inserted output elements of one block.
std::vector<ContourElement> OfTag(const std::vector<ContourElement>& out, int64_t tag) {
  std::vector<ContourElement> found;
  for (const ContourElement& e : out)
    if (e.tag == tag && !e.inserted) found.push_back(e);
  return found;
}

std::vector<ContourElement> Inserted(const std::vector<ContourElement>& out) {
  std::vector<ContourElement> found;
  for (const ContourElement& e : out)
    if (e.inserted) found.push_back(e);
  return found;
}

const char* KindName(Kind k) {
  return k == Kind::kLine ? "line" : k == Kind::kArcCw ? "G02" : "G03";
}

// CSV dump of a path for plotting a failure: kind, start, end, centre (z, x), tag, inserted.
std::string Csv(const std::vector<ContourElement>& path) {
  std::string csv = "kind,start_z,start_x,end_z,end_x,centre_z,centre_x,tag,inserted\n";
  char line[320];
  for (const ContourElement& e : path) {
    std::snprintf(line, sizeof line, "%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%lld,%d\n",
                  KindName(e.kind), e.start.z, e.start.x, e.end.z, e.end.x, e.centre.z, e.centre.x,
                  static_cast<long long>(e.tag), e.inserted ? 1 : 0);
    csv += line;
  }
  return csv;
}

std::string Str(Vec2 p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.17g, %.17g)", p.z, p.x);
  return s;
}

::testing::AssertionResult Near(Vec2 actual, Vec2 expected, double tol = kTol) {
  if (std::abs(actual.z - expected.z) <= tol && std::abs(actual.x - expected.x) <= tol)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << Str(actual) << " != " << Str(expected) << " (tolerance " << tol << ")";
}

// ---------------------------------------------------------------------------------------------
// Independent geometry for the checks.

Vec2 Rotate(Vec2 v, double a) {
  return {v.z * std::cos(a) - v.x * std::sin(a), v.z * std::sin(a) + v.x * std::cos(a)};
}
Vec2 LeftOf(Vec2 v) { return {-v.x, v.z}; }
Vec2 UnitOf(Vec2 v) { return (1 / Norm(v)) * v; }

// Distance from a point to a line segment or to an arc (the piece between its end points).
double DistanceToElement(Vec2 p, const ContourElement& e) {
  if (e.kind == Kind::kLine) {
    const Vec2 d = e.end - e.start;
    const double length2 = Dot(d, d);
    double t = length2 > 0 ? Dot(p - e.start, d) / length2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return Norm(p - (e.start + t * d));
  }
  const double sweep = ArcSweep(e);
  const double radius = Norm(e.start - e.centre);
  const double a0 = std::atan2(e.start.x - e.centre.x, e.start.z - e.centre.z);
  const double a = std::atan2(p.x - e.centre.x, p.z - e.centre.z);
  double travelled = (sweep > 0 ? 1 : -1) * (a - a0);
  travelled = std::fmod(travelled, 2 * kPi);
  if (travelled < 0) travelled += 2 * kPi;
  if (travelled <= std::abs(sweep)) return std::abs(Norm(p - e.centre) - radius);
  return std::min(Norm(p - e.start), Norm(p - e.end));
}

// n + 1 points along an output element, start and end included.
std::vector<Vec2> Samples(const ContourElement& e, int n = 16) {
  std::vector<Vec2> points;
  const double sweep = ArcSweep(e);
  for (int i = 0; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    if (e.kind == Kind::kLine)
      points.push_back(e.start + u * (e.end - e.start));
    else
      points.push_back(e.centre + Rotate(e.start - e.centre, u * sweep));
  }
  return points;
}

bool IsZeroLength(const ContourElement& e) {
  return e.kind == Kind::kLine && Norm(e.end - e.start) <= kTol;
}

// What each programmed block is for the compensation, found from the modal states alone.
enum class Role { kPass, kStartUp, kCancel, kSideChange, kCompensated, kZero };

std::vector<Role> Roles(const std::vector<ContourElement>& in) {
  std::vector<Role> roles;
  bool active = false;
  Side side = Side::kOff;
  for (const ContourElement& e : in) {
    if (IsZeroLength(e)) {
      roles.push_back(Role::kZero);
    } else if (!active) {
      roles.push_back(e.side == Side::kOff ? Role::kPass : Role::kStartUp);
      active = e.side != Side::kOff;
    } else if (e.side == Side::kOff) {
      roles.push_back(Role::kCancel);
      active = false;
    } else {
      roles.push_back(e.side == side ? Role::kCompensated : Role::kSideChange);
    }
    if (!IsZeroLength(e) && active) side = e.side;
  }
  return roles;
}

// Invariants of a finished run without error:
// - every block comes out once, in order, plus inserted elements;
// - the path is continuous; output arcs have one radius;
// - under G40 blocks pass unchanged; start-up starts and cancel ends at the programmed points;
// - the nose centre (tip - TipFromCentre) of every compensated element is at r from its block,
//   of every transition arc at r from the corner point, of every run back at r from the block
//   it runs back on; compensated elements run forwards, lines parallel, arcs concentric with
//   the offset radius R -+ r and no longer than programmed;
// - with `neighbours`: no nose-centre point comes closer than r to the programmed block it
//   belongs to nor to the compensated blocks before and after it (no gouge at the corners).
::testing::AssertionResult CheckPath(const std::vector<ContourElement>& in,
                                     const std::vector<ContourElement>& out, bool neighbours) {
  const std::vector<Role> roles = Roles(in);
  auto fail = [&](size_t i, const std::string& what) {
    return ::testing::AssertionFailure()
           << "output element " << i << " (tag " << out[i].tag << ", " << KindName(out[i].kind)
           << (out[i].inserted ? ", inserted" : "") << "): " << what;
  };
  // Moving compensated neighbours of a block.
  auto neighbour = [&](int64_t tag, int step) -> const ContourElement* {
    for (int64_t k = tag + step; k >= 0 && k < static_cast<int64_t>(in.size()); k += step) {
      if (roles[k] == Role::kZero) continue;
      if (roles[k] == Role::kCompensated) return &in[k];
      return nullptr;
    }
    return nullptr;
  };
  int64_t next_tag = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const ContourElement& e = out[i];
    if (i > 0 && !Near(e.start, out[i - 1].end))
      return fail(i, "starts at " + Str(e.start) + ", previous ends at " + Str(out[i - 1].end));
    if (e.kind != Kind::kLine && std::abs(Norm(e.start - e.centre) - Norm(e.end - e.centre)) > kTol)
      return fail(i, "arc radius differs at start and end");
    if (e.tag < 0 || e.tag >= static_cast<int64_t>(in.size())) return fail(i, "unknown tag");
    const ContourElement& p = in[e.tag];
    const Vec2 tip = TipFromCentre(p.edge_position, p.nose_radius_mm);
    const double r = p.nose_radius_mm;
    std::vector<const ContourElement*> near_elements;
    if (e.inserted) {
      if (e.tag != next_tag) return fail(i, "inserted element not before its block");
      const ContourElement* before = neighbour(e.tag, -1);
      if (roles[e.tag] != Role::kCompensated || !before)
        return fail(i, "inserted element outside a compensated contour");
      const bool transition = e.kind != Kind::kLine && Near(e.centre, p.start + tip);
      for (Vec2 q : Samples(e)) {
        const double d = transition ? Norm(q - tip - p.start) : DistanceToElement(q - tip, *before);
        if (std::abs(d - r) > kTol)
          return fail(i, "nose centre " + Str(q - tip) + " at " + std::to_string(d) + " from the " +
                             (transition ? "corner" : "block run back on"));
      }
      near_elements = {before, &p};
    } else {
      if (e.tag != next_tag)
        return fail(i, "out of order, expected tag " + std::to_string(next_tag));
      ++next_tag;
      switch (roles[e.tag]) {
        case Role::kPass:
          if (!Near(e.start, p.start) || !Near(e.end, p.end) || e.kind != p.kind)
            return fail(i, "G40 block changed");
          break;
        case Role::kZero:
          if (!IsZeroLength(e)) return fail(i, "zero-length block moves");
          break;
        case Role::kStartUp:
        case Role::kSideChange: {
          if (roles[e.tag] == Role::kStartUp && !Near(e.start, p.start))
            return fail(i, "start-up does not start at the programmed point");
          const double d = Norm(e.end - tip - p.end);
          if (std::abs(d - r) > kTol) return fail(i, "start-up end not at r from its end point");
          if (const ContourElement* next = neighbour(e.tag, +1);
              next && std::abs(DistanceToElement(e.end - tip, *next) - r) > kTol)
            return fail(i, "start-up end not at r from the next block");
          break;
        }
        case Role::kCancel: {
          if (!Near(e.end, p.end)) return fail(i, "cancel does not end at the programmed point");
          break;
        }
        case Role::kCompensated: {
          for (Vec2 q : Samples(e)) {
            const double d = DistanceToElement(q - tip, p);
            if (std::abs(d - r) > kTol)
              return fail(i, "nose centre " + Str(q - tip) + " at " + std::to_string(d) +
                                 " from its block, r " + std::to_string(r));
          }
          if (p.kind == Kind::kLine) {
            const Vec2 d = UnitOf(p.end - p.start);
            if (e.kind != Kind::kLine) return fail(i, "line became an arc");
            if (Dot(e.end - e.start, d) < -kTol) return fail(i, "runs backwards");
            if (std::abs(Cross(e.end - e.start, d)) > kTol) return fail(i, "not parallel");
          } else if (e.kind == Kind::kLine) {
            if (Norm(e.end - e.start) > kTol) return fail(i, "arc became a line");
          } else {
            const double sigma = p.kind == Kind::kArcCcw ? 1 : -1;
            const double s = p.side == Side::kLeft ? 1 : -1;
            const double expected = Norm(p.start - p.centre) - sigma * s * r;
            if (e.kind != p.kind) return fail(i, "arc direction changed");
            if (!Near(e.centre, p.centre + tip)) return fail(i, "arc centre moved");
            if (std::abs(Norm(e.start - e.centre) - expected) > kTol)
              return fail(i, "offset arc radius " + std::to_string(Norm(e.start - e.centre)) +
                                 ", expected " + std::to_string(expected));
            if (std::abs(ArcSweep(e)) > std::abs(ArcSweep(p)) + kTol)
              return fail(i, "longer than programmed");
          }
          near_elements = {&p, neighbour(e.tag, -1), neighbour(e.tag, +1)};
          break;
        }
      }
    }
    if (!neighbours) continue;
    for (const ContourElement* n : near_elements) {
      if (!n) continue;
      for (Vec2 q : Samples(e, 64)) {
        const double d = DistanceToElement(q - tip, *n);
        if (d < r - kTol)
          return fail(i, "gouge: nose centre " + Str(q - tip) + " at " + std::to_string(d) +
                             " from block " + std::to_string(n->tag));
      }
    }
  }
  if (next_tag != static_cast<int64_t>(in.size()))
    return ::testing::AssertionFailure()
           << "only " << next_tag << " of " << in.size() << " blocks came out";
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// Conventions.

TEST(ToolRadiusCompensationTest, TipFromCentreTable) {
  const double r = 0.8;
  const Vec2 expected[10] = {{0, 0}, {r, r},  {-r, r}, {-r, -r}, {r, -r},
                             {0, r}, {-r, 0}, {0, -r}, {r, 0},   {0, 0}};
  for (int edge = 0; edge <= 9; ++edge)
    EXPECT_TRUE(Near(TipFromCentre(edge, r), expected[edge])) << "edge " << edge;
  EXPECT_TRUE(Near(TipFromCentre(10, r), {0, 0}));
  EXPECT_TRUE(Near(TipFromCentre(-1, r), {0, 0}));
}

TEST(ToolRadiusCompensationTest, ArcSweepConvention) {
  ContourElement arc;
  arc.kind = Kind::kArcCcw;  // counter-clockwise: from +Z towards +X
  arc.centre = {0, 0};
  arc.start = {1, 0};
  arc.end = {0, 1};
  EXPECT_NEAR(ArcSweep(arc), kPi / 2, 1e-15);
  arc.kind = Kind::kArcCw;
  EXPECT_NEAR(ArcSweep(arc), -3 * kPi / 2, 1e-15);
  arc.end = arc.start;
  EXPECT_NEAR(ArcSweep(arc), -2 * kPi, 1e-15);
  arc.kind = Kind::kArcCcw;
  EXPECT_NEAR(ArcSweep(arc), 2 * kPi, 1e-15);
  arc.kind = Kind::kLine;
  EXPECT_EQ(ArcSweep(arc), 0);
}

// ---------------------------------------------------------------------------------------------
// Outside turning on a lathe, G42, edge position 3 (tip at (-r, -r) from the nose centre).

// Rapid to the start, start-up onto the diameter 2*20, turn it towards the chuck, shoulder up
// to the diameter 2*30 (inner corner), turn that (outer corner at the shoulder edge), cancel.
Program OutsideDiameterAndShoulder(int edge = 3) {
  Program p;
  p.edge = edge;
  p.From(120, 30);
  p.rapid = true;
  p.Line(105, 25);  // 0: G40 rapid
  p.rapid = false;
  p.G42().Line(100, 20);  // 1: start-up
  p.Line(50, 20);         // 2: diameter, -Z
  p.Line(50, 30);         // 3: shoulder face, +X
  p.Line(20, 30);         // 4: diameter, -Z
  p.G40().Line(15, 40);   // 5: cancel
  return p;
}

TEST(ToolRadiusCompensationTest, OutsideDiameterG42Edge3PutsTheTipOnTheContour) {
  // Moving -Z, the left (+90 degrees) is -X, the material; the tool is on the right: G42.
  const Program p = OutsideDiameterAndShoulder();
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_EQ(run.out.size(), 7u) << Csv(run.out);
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);

  // G40 rapid unchanged.
  EXPECT_TRUE(Near(run.out[0].start, {120, 30}));
  EXPECT_TRUE(Near(run.out[0].end, {105, 25}));
  EXPECT_TRUE(run.out[0].rapid);
  // Start-up: from the programmed start to the nose centre (100, 20.8) perpendicular to the
  // diameter, i.e. the tip (99.2, 20.0).
  EXPECT_EQ(run.out[1].tag, 1);
  EXPECT_TRUE(Near(run.out[1].start, {105, 25}));
  EXPECT_TRUE(Near(run.out[1].end, {99.2, 20}));
  // The diameter: nose centre at X 20.8, tip at X 20.0, exactly the programmed diameter; it
  // ends at the inner shoulder corner, nose centre (50.8, 20.8), tip (50, 20).
  EXPECT_EQ(run.out[2].tag, 2);
  EXPECT_TRUE(Near(run.out[2].start, {99.2, 20}));
  EXPECT_TRUE(Near(run.out[2].end, {50, 20}));
  EXPECT_TRUE(Near(run.out[2].start - TipFromCentre(3, 0.8), {100, 20.8}));
  // The shoulder face (+X at Z 50, tool on +Z): nose centre at Z 50.8, tip at Z 50.0.
  EXPECT_EQ(run.out[3].tag, 3);
  EXPECT_TRUE(Near(run.out[3].start, {50, 20}));
  EXPECT_TRUE(Near(run.out[3].end, {50, 29.2}));
  // Outer corner at (50, 30): transition arc r 0.8 around the corner (centre (50, 30) + tip
  // offset), G03 under G42, tagged with the block after it.
  const ContourElement& arc = run.out[4];
  EXPECT_TRUE(arc.inserted);
  EXPECT_EQ(arc.tag, 4);
  EXPECT_EQ(arc.kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(arc.centre, {49.2, 29.2}));
  EXPECT_TRUE(Near(arc.start, {50, 29.2}));
  EXPECT_TRUE(Near(arc.end, {49.2, 30}));
  EXPECT_NEAR(ArcSweep(arc), kPi / 2, 1e-12);
  // The second diameter: tip at X 30.0; it ends perpendicular before the cancel.
  EXPECT_EQ(run.out[5].tag, 4);
  EXPECT_TRUE(Near(run.out[5].start, {49.2, 30}));
  EXPECT_TRUE(Near(run.out[5].end, {19.2, 30}));
  // Cancel: from the offset end to the programmed end point.
  EXPECT_EQ(run.out[6].tag, 5);
  EXPECT_TRUE(Near(run.out[6].start, {19.2, 30}));
  EXPECT_TRUE(Near(run.out[6].end, {15, 40}));
}

TEST(ToolRadiusCompensationTest, FrontFaceMovingMinusXIsG41ForAnEdge3Tool) {
  // Facing the front face at Z 50 towards the axis (-X): the left of -X is +Z, where the tool
  // is, so this is G41; with edge position 3 the tip runs at Z 50.0 (nose centre Z 50.8).
  Program p;
  p.From(60, 25).G41().Line(50, 20);  // 0: start-up
  p.Line(50, 0);                      // 1: face
  p.G40().Line(60, 2);                // 2: cancel
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_EQ(run.out.size(), 3u) << Csv(run.out);
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  EXPECT_TRUE(Near(run.out[1].start, {50, 19.2}));
  EXPECT_TRUE(Near(run.out[1].end, {50, -0.8}));
  EXPECT_TRUE(Near(run.out[1].start - TipFromCentre(3, 0.8), {50.8, 20}));
}

TEST(ToolRadiusCompensationTest, DescendingShoulderUnderG42PutsTheNoseOnMinusZ) {
  // Under G42 a face moving -X has the tool on its right, -Z: a step down towards the chuck.
  // The corner at its top is outer, at its foot inner. An edge-3 tool does not fit that face:
  // its nose centre runs at Z 49.2 and its theoretical tip at Z 48.4 (by the table; a tool for
  // that face would be edge position 4).
  Program p;
  p.From(110, 35).G42().Line(100, 30);  // 0: start-up
  p.Line(50, 30);                       // 1
  p.Line(50, 20);                       // 2: face, -X
  p.Line(20, 20);                       // 3
  p.G40().Line(15, 30);                 // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> face = OfTag(run.out, 2);
  ASSERT_EQ(face.size(), 1u);
  const Vec2 tip = TipFromCentre(3, 0.8);
  EXPECT_TRUE(Near(face[0].start - tip, {49.2, 30}));
  EXPECT_TRUE(Near(face[0].end - tip, {49.2, 20.8}));
  EXPECT_NEAR(face[0].start.z, 48.4, kTol);
  const std::vector<ContourElement> arcs = Inserted(run.out);
  ASSERT_EQ(arcs.size(), 1u);  // only the outer corner at (50, 30)
  EXPECT_EQ(arcs[0].tag, 2);
  EXPECT_EQ(arcs[0].kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(arcs[0].centre - tip, {50, 30}));
}

TEST(ToolRadiusCompensationTest, EdgePositionsOnlyShiftTheNoseCentrePath) {
  const Result reference = Compensate(OutsideDiameterAndShoulder(0).blocks);
  ASSERT_FALSE(reference.error);
  for (int edge = 1; edge <= 9; ++edge) {
    SCOPED_TRACE("edge position " + std::to_string(edge));
    const Program p = OutsideDiameterAndShoulder(edge);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    ASSERT_EQ(run.out.size(), reference.out.size());
    const Vec2 tip = TipFromCentre(edge, 0.8);
    for (size_t i = 1; i < run.out.size(); ++i) {
      const ContourElement &a = run.out[i], &b = reference.out[i];
      EXPECT_EQ(a.kind, b.kind);
      EXPECT_EQ(a.tag, b.tag);
      // The start-up starts and the cancel ends at programmed (uncompensated) points.
      EXPECT_TRUE(Near(a.start - (i == 1 ? Vec2{} : tip), b.start)) << i;
      EXPECT_TRUE(Near(a.end - (i == run.out.size() - 1 ? Vec2{} : tip), b.end)) << i;
      if (a.kind != Kind::kLine) {
        EXPECT_TRUE(Near(a.centre - tip, b.centre)) << i;
      }
    }
  }
  // Edge 3 puts the tip on the diameters and faces of this contour; edge 9 is the centre.
  const Result edge9 = Compensate(OutsideDiameterAndShoulder(9).blocks);
  EXPECT_TRUE(Near(edge9.out[2].start, {100, 20.8}));
}

// ---------------------------------------------------------------------------------------------
// Corners with arcs.

// A stepped shaft under G42: a G02 fillet into a shoulder and a G03 fillet onto the next
// diameter (both tangent), a G03 that starts at an inner corner (not tangent), a G02 cove
// that starts at an outer corner.
Program SteppedShaft() {
  Program p;
  p.From(105, 12).G42().Line(100, 10);  // 0: start-up
  p.Line(60, 10);                       // 1: diameter
  p.Cw(58, 12, 60, 12);                 // 2: concave fillet R2, tangent
  p.Line(58, 18);                       // 3: shoulder face
  p.Ccw(56, 20, 56, 18);                // 4: convex fillet R2, tangent
  p.Line(30, 20);                       // 5: diameter
  p.Ccw(25, 25, 25, 20);                // 6: R5, starts at an inner corner
  p.Line(10, 25);                       // 7: tangent
  p.Cw(5, 20, 5, 25);                   // 8: cove R5, starts at an outer corner
  p.Line(0, 20);                        // 9: tangent
  p.G40().Line(-5, 30);                 // 10: cancel
  return p;
}

TEST(ToolRadiusCompensationTest, SteppedShaftWithFillets) {
  const Program p = SteppedShaft();
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const Vec2 tip = TipFromCentre(3, 0.8);
  // Tangent fillets: nothing inserted; offset arcs concentric, R 2 - 0.8 inside the concave
  // one, 2 + 0.8 outside the convex one.
  const ContourElement fillet_in = OfTag(run.out, 2).at(0);
  EXPECT_EQ(fillet_in.kind, Kind::kArcCw);
  EXPECT_TRUE(Near(fillet_in.centre - tip, {60, 12}));
  EXPECT_NEAR(Norm(fillet_in.start - fillet_in.centre), 1.2, kTol);
  EXPECT_TRUE(Near(fillet_in.start - tip, {60, 10.8}));
  EXPECT_TRUE(Near(fillet_in.end - tip, {58.8, 12}));
  const ContourElement fillet_out = OfTag(run.out, 4).at(0);
  EXPECT_EQ(fillet_out.kind, Kind::kArcCcw);
  EXPECT_NEAR(Norm(fillet_out.start - fillet_out.centre), 2.8, kTol);
  EXPECT_TRUE(Near(fillet_out.end - tip, {56, 20.8}));
  // Inner corner line -> arc at (30, 20): the line X 20.8 meets the circle R 5.8 around
  // (25, 20) at Z 25 + sqrt(5.8^2 - 0.8^2).
  const Vec2 meet{25 + std::sqrt(5.8 * 5.8 - 0.8 * 0.8), 20.8};
  EXPECT_TRUE(Near(OfTag(run.out, 5).at(0).end - tip, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 6).at(0).start - tip, meet));
  EXPECT_NEAR(Norm(OfTag(run.out, 6).at(0).start - OfTag(run.out, 6).at(0).centre), 5.8, kTol);
  // Outer corner line -> arc at (10, 25): one transition arc, G03 under G42, from above the
  // corner to the cove's offset start (9.2, 25), which is on the cove's inner offset R 4.2.
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u) << Csv(run.out);
  EXPECT_EQ(inserted[0].tag, 8);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(inserted[0].centre - tip, {10, 25}));
  EXPECT_TRUE(Near(inserted[0].start - tip, {10, 25.8}));
  EXPECT_TRUE(Near(inserted[0].end - tip, {9.2, 25}));
  const ContourElement cove = OfTag(run.out, 8).at(0);
  EXPECT_NEAR(Norm(cove.start - cove.centre), 4.2, kTol);
  EXPECT_TRUE(Near(cove.end - tip, {5, 20.8}));
}

TEST(ToolRadiusCompensationTest, ArcArcInnerCorner) {
  // Two G02 bumps R10 meeting in a valley at (5, 5*sqrt(3)), tool above (G41): the offset
  // circles R10.8 around (0, 0) and (10, 0) meet at (5, sqrt(10.8^2 - 25)).
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.From(-5, 15).G41().Line(-5, h);  // 0: start-up
  p.Cw(5, h, 0, 0);                  // 1
  p.Cw(15, h, 10, 0);                // 2
  p.G40().Line(20, 15);              // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  EXPECT_TRUE(Inserted(run.out).empty());
  const Vec2 meet{5, std::sqrt(10.8 * 10.8 - 25)};
  EXPECT_TRUE(Near(OfTag(run.out, 1).at(0).end, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 2).at(0).start, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 1).at(0).start, {-5.4, 0.54 * 2 * h}));
}

TEST(ToolRadiusCompensationTest, ArcArcOuterCornerInsertsAnArc) {
  // Two G03 dips R10 meeting at a peak (5, -5*sqrt(3)), tool above (G41, inside the circles):
  // the tool goes over the peak on an arc of the nose radius, G02 under G41.
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.r = 0.5;
  p.From(-5, -15).G41().Line(-5, -h);  // 0: start-up
  p.Ccw(5, -h, 0, 0);                  // 1: from 240 to 300 degrees
  p.Ccw(15, -h, 10, 0);                // 2
  p.G40().Line(20, -15);               // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCw);
  EXPECT_TRUE(Near(inserted[0].centre, {5, -h}));
  EXPECT_NEAR(ArcSweep(inserted[0]), -kPi / 3, 1e-12);
  EXPECT_NEAR(Norm(OfTag(run.out, 1).at(0).start - OfTag(run.out, 1).at(0).centre), 9.5, kTol);
}

TEST(ToolRadiusCompensationTest, ReversalGoesAroundTheEndOnASemicircle) {
  Program p;
  p.edge = 0;
  p.r = 1;
  p.From(-10, 5).G41().Line(0, 0);  // 0
  p.Line(10, 0);                    // 1: +Z, tool at +X
  p.Line(0, 0);                     // 2: back, tool at -X
  p.G40().Line(-5, 5);              // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCw);
  EXPECT_TRUE(Near(inserted[0].start, {10, 1}));
  EXPECT_TRUE(Near(inserted[0].end, {10, -1}));
  EXPECT_TRUE(Near(Samples(inserted[0], 2)[1], {11, 0}));
}

TEST(ToolRadiusCompensationTest, FullCircleStaysAFullCircle) {
  Program p;
  p.edge = 0;
  p.From(-10, -5).G42().Line(-5, 0);  // 0
  p.Line(0, 0);                       // 1: +Z, tool below
  p.Ccw(0, 0, 0, 5);                  // 2: full circle above, tool outside: R 5.8
  p.Line(5, 0);                       // 3
  p.G40().Line(10, -5);               // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  // A full circle closes on itself and passes within r of the line before it, which one
  // element of look-ahead cannot see: only the element's own distance is checked.
  EXPECT_TRUE(CheckPath(p.blocks, run.out, false)) << Csv(run.out);
  const ContourElement circle = OfTag(run.out, 2).at(0);
  EXPECT_EQ(circle.kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(circle.start, {0, -0.8}));
  EXPECT_TRUE(Near(circle.end, {0, -0.8}));
  EXPECT_NEAR(ArcSweep(circle), 2 * kPi, 1e-12);
  EXPECT_TRUE(Inserted(run.out).empty());
}

// ---------------------------------------------------------------------------------------------
// Start-up, cancel, side and correction changes.

TEST(ToolRadiusCompensationTest, StartUpEndsPerpendicularToTheFollowingArc) {
  Program p;
  p.edge = 0;
  p.From(0, 20).G42().Line(0, 10);  // 0: start-up, -X
  p.Cw(-5, 5, -5, 10);              // 1: G02 R5, starts moving -X, tool inside: R 4.2
  p.G40().Line(-10, 20);            // 2
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const ContourElement start_up = OfTag(run.out, 0).at(0);
  EXPECT_TRUE(Near(start_up.start, {0, 20}));
  EXPECT_TRUE(Near(start_up.end, {-0.8, 10}));
  const ContourElement arc = OfTag(run.out, 1).at(0);
  EXPECT_TRUE(Near(arc.start, {-0.8, 10}));
  EXPECT_TRUE(Near(arc.end, {-5, 5.8}));
  EXPECT_NEAR(ArcSweep(arc), -kPi / 2, 1e-12);
  EXPECT_TRUE(Inserted(run.out).empty());
}

TEST(ToolRadiusCompensationTest, StartUpOnAnArcIsAnError) {
  Program p;
  p.From(10, 10).Line(0, 10);
  p.G41().Cw(-10, 10, -5, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 1);
  EXPECT_EQ(run.error->message,
            "G41/G42 start-up on an arc: the block that starts tool nose radius compensation "
            "must be a straight line (G00/G01)");
  ASSERT_EQ(run.out.size(), 1u);  // the G40 block before it
}

TEST(ToolRadiusCompensationTest, CancelOnAnArcIsAnError) {
  Program p;
  p.From(10, 10).G41().Line(0, 10);
  p.Line(-10, 10);
  p.G40().Ccw(-20, 10, -15, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "G40 cancel on an arc: the block that cancels tool nose radius compensation must be "
            "a straight line (G00/G01)");
}

TEST(ToolRadiusCompensationTest, SideChangeIsCancelAndStartUpInOneBlock) {
  Program p;
  p.edge = 0;
  p.From(-20, 5).G41().Line(-10, 10);  // 0: start-up
  p.Line(0, 10);                       // 1: +Z, tool on +X: X 10.8
  p.G42();
  p.r = 0.4;             // a new correction may come with the side change
  p.Line(10, 10);        // 2: side change
  p.Line(20, 10);        // 3: +Z, tool on -X: X 9.6
  p.G40().Line(25, 15);  // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  ASSERT_EQ(run.out.size(), 5u) << Csv(run.out);
  EXPECT_TRUE(Near(run.out[1].end, {0, 10.8}));    // ends perpendicular before the change
  EXPECT_TRUE(Near(run.out[2].start, {0, 10.8}));  // side change from there ...
  EXPECT_TRUE(Near(run.out[2].end, {10, 9.6}));    // ... to the new side, perpendicular
  EXPECT_TRUE(Near(run.out[3].start, {10, 9.6}));  // to the next block
  EXPECT_TRUE(Near(run.out[4].start, {20, 9.6}));
  EXPECT_TRUE(Near(run.out[4].end, {25, 15}));
}

TEST(ToolRadiusCompensationTest, SideChangeOnAnArcIsAnError) {
  Program p;
  p.From(-20, 5).G41().Line(-10, 10);
  p.Line(0, 10);
  p.G42().Cw(10, 10, 5, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "G41/G42 side change on an arc: the block that changes the compensation side must "
            "be a straight line (G00/G01)");
}

TEST(ToolRadiusCompensationTest, CorrectionChangeWhileActiveIsAnError) {
  {
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.r = 0.4;
    p.Line(10, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 2);
    EXPECT_EQ(run.error->message,
              "tool nose radius changed while G41/G42 is active (r 0.8 -> 0.4 mm): cancel with "
              "G40 first");
  }
  {
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.edge = 2;
    p.Line(10, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 2);
    EXPECT_EQ(run.error->message,
              "cutting edge position changed while G41/G42 is active (3 -> 2): cancel with G40 "
              "first");
  }
  {
    // A new correction on the cancel block and at the next start-up is fine.
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.r = 0.4;
    p.G40().Line(5, 15);
    p.G42().Line(10, 10);
    p.Line(20, 10);
    p.G40().Line(25, 15);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  }
}

TEST(ToolRadiusCompensationTest, BadInputIsAnError) {
  {
    Program p;
    p.edge = 12;
    p.From(0, 5).G41().Line(0, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->message, "invalid cutting edge position 12 (0..9)");
  }
  {
    Program p;
    p.r = -0.4;
    p.From(0, 5).G41().Line(0, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->message, "negative tool nose radius -0.4 mm");
  }
  {
    Program p;
    p.From(0, 5).G41().Line(0, 10);
    p.From(0.5, 10).Line(20, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message,
              "contour not continuous under G41/G42: the block starts 0.5 mm away from the "
              "previous end point");
  }
  {
    Program p;
    p.From(0, 5).G41().Line(0, 10);
    p.Cw(5, 15, 0, 10);  // centre on the start point
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message, "arc centre on the arc start point");
  }
  {
    // Under G40 nothing is checked: the blocks pass unchanged.
    Program p;
    p.edge = 12;
    p.From(0, 5).Line(0, 10);
    p.From(3, 3).Cw(5, 5, 3, 3);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error);
    ASSERT_EQ(run.out.size(), 2u);
    EXPECT_TRUE(Near(run.out[1].start, {3, 3}));
    EXPECT_EQ(run.out[1].kind, Kind::kArcCw);
  }
}

TEST(ToolRadiusCompensationTest, ArcEndPointOffTheCircleIsPutOnIt) {
  // End point 0.005 mm off the circle (the channel accepts 0.01): the radius is taken at the
  // start, the path stays continuous.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G42().Line(-5, 0);  // 0
  p.Line(0, 0);                      // 1
  p.Ccw(5, 5.005, 0, 5);             // 2: R5 quarter, end 0.005 off
  p.Line(5, 10);                     // 3
  p.G40().Line(10, 15);              // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  for (size_t i = 1; i < run.out.size(); ++i)
    EXPECT_TRUE(Near(run.out[i].start, run.out[i - 1].end)) << i;
  const ContourElement arc = OfTag(run.out, 2).at(0);
  EXPECT_NEAR(Norm(arc.start - arc.centre), 5.8, kTol);
  EXPECT_NEAR(Norm(arc.end - arc.centre), 5.8, kTol);
}

// ---------------------------------------------------------------------------------------------
// Gouges and arcs the nose does not fit in.

// A groove of width w and depth 5 in the diameter 2*20, G42, edge 3.
Program Groove(double w) {
  Program p;
  p.From(110, 25).G42().Line(100, 20);  // 0
  p.Line(60, 20);                       // 1
  p.Line(60, 15);                       // 2: groove flank, -X (outer corner above)
  p.Line(60 - w, 15);                   // 3: groove bottom (inner corners at both ends)
  p.Line(60 - w, 20);                   // 4: flank, +X
  p.Line(30, 20);                       // 5
  p.G40().Line(25, 30);                 // 6
  return p;
}

TEST(ToolRadiusCompensationTest, GrooveWideEnoughForTheNose) {
  const Program p = Groove(2);
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  // Bottom: nose centre from Z 59.2 to 58.8 at X 15.8: 2 - 2 * 0.8 long.
  const ContourElement bottom = OfTag(run.out, 3).at(0);
  const Vec2 tip = TipFromCentre(3, 0.8);
  EXPECT_TRUE(Near(bottom.start - tip, {59.2, 15.8}));
  EXPECT_TRUE(Near(bottom.end - tip, {58.8, 15.8}));
  EXPECT_EQ(Inserted(run.out).size(), 2u);  // the outer corners at the groove's edges
}

TEST(ToolRadiusCompensationTest, GrooveNarrowerThanTheNoseIsAGouge) {
  const Program p = Groove(1);  // needs 1.6
  ToolRadiusCompensation trc;
  std::vector<ContourElement> out;
  ContourElement e;
  for (const ContourElement& b : p.blocks) {
    trc.Push(b);
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_TRUE(trc.error());
  EXPECT_EQ(trc.error()->tag, 3);
  EXPECT_EQ(trc.error()->message,
            "contour violation (gouge): the block is too short for the tool nose radius 0.8 mm "
            "at an inner corner, the compensated path would run backwards");
  // What was final before the error stays: start-up, diameter, corner arc, flank.
  ASSERT_EQ(out.size(), 4u) << Csv(out);
  EXPECT_EQ(out.back().tag, 2);
  EXPECT_FALSE(trc.pending());
  for (size_t i = 1; i < out.size(); ++i) EXPECT_TRUE(Near(out[i].start, out[i - 1].end));
  // Stopped for good until Reset.
  trc.Push(p.blocks[0]);
  EXPECT_FALSE(trc.Pop(e));
  trc.Reset();
  EXPECT_FALSE(trc.error());
  trc.Push(p.blocks[0]);
  EXPECT_TRUE(trc.pending());
}

TEST(ToolRadiusCompensationTest, ShortBlockAfterAnOuterCornerIsAGouge) {
  // Outer corner then a block too short for the inner corner after it: the intersection lies
  // before the block's offset start.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G41().Line(0, 0);  // 0
  p.Line(10, 0);                    // 1: +Z, tool at +X
  p.Line(10, -0.5);                 // 2: -X, outer corner; 0.5 long
  p.Line(20, -0.5);                 // 3: +Z, inner corner needs 0.8 on block 2
  p.G40().Line(25, 5);              // 4
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_THAT(run.error->message, HasSubstr("too short for the tool nose radius 0.8 mm"));
}

TEST(ToolRadiusCompensationTest, ArcSmallerThanTheNoseOnTheInnerSideIsAnError) {
  // +Z, then a G03 half circle R0.5 up and back -Z: G41 puts the nose inside it.
  auto program = [](Side side, double r) {
    Program p;
    p.edge = 0;
    p.r = r;
    p.side = side;
    p.From(-10, 0).Line(0, 0);  // 0: start-up
    p.Ccw(0, 1, 0, 0.5);        // 1
    p.Line(-10, 1);             // 2
    p.G40().Line(-15, 5);       // 3
    return p;
  };
  {
    const Result run = Compensate(program(Side::kLeft, 0.8).blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message,
              "arc radius 0.5 mm smaller than the tool nose radius 0.8 mm on the inner side of "
              "the arc");
  }
  {
    // Outside it (G42) the nose runs on R 1.3.
    const Program p = program(Side::kRight, 0.8);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    EXPECT_NEAR(Norm(OfTag(run.out, 1).at(0).start - OfTag(run.out, 1).at(0).centre), 1.3, kTol);
  }
  {
    // Exactly the nose radius inside: the nose centre stands on the arc centre; the block
    // comes out as a zero-length line there.
    const Program p = program(Side::kLeft, 0.5);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    const ContourElement still = OfTag(run.out, 1).at(0);
    EXPECT_EQ(still.kind, Kind::kLine);
    EXPECT_TRUE(Near(still.start, {0, 0.5}));
    EXPECT_TRUE(Near(still.end, {0, 0.5}));
    EXPECT_TRUE(Inserted(run.out).empty());
  }
}

TEST(ToolRadiusCompensationTest, InnerCornerIntoATightArcWithoutIntersectionIsAGouge) {
  // +Z along X 0 with the tool above (G41), then a G03 R1 turning up steeply: the offset line
  // X 0.8 and the offset circle R 0.2 do not meet.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G41().Line(-5, 0);  // 0
  p.Line(0, 0);                      // 1
  // Tangent at (0, 0) pointing up-left (turn 135 degrees left): centre at 1 * left of it.
  const Vec2 t = UnitOf({-1, 1});
  const Vec2 c = Vec2{0, 0} + LeftOf(t);
  const Vec2 end = c + Rotate(Vec2{0, 0} - c, kPi / 2);
  p.Ccw(end.z, end.x, c.z, c.x);  // 2
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "contour violation (gouge): the offset contour has no intersection at the inner "
            "corner, the tool nose radius 0.8 mm does not fit");
}

// ---------------------------------------------------------------------------------------------
// Blocks without motion, stops, streaming, pass-through.

TEST(ToolRadiusCompensationTest, ZeroLengthBlocksKeepTheirPlaceAndTheCorner) {
  const Program plain = OutsideDiameterAndShoulder();
  const Result reference = Compensate(plain.blocks);
  ASSERT_FALSE(reference.error);
  // The same contour with a block without motion at the inner corner (after block 2) and at
  // the outer corner (after block 3), and one under G41 before the start-up (the modal G42
  // takes effect on the next moving block).
  Program p;
  p.From(120, 30);
  p.rapid = true;
  p.Line(105, 25);  // 0
  p.rapid = false;
  p.G42().Line(105, 25);  // 1: no motion
  p.Line(100, 20);        // 2: start-up
  p.Line(50, 20);         // 3
  p.Line(50, 20);         // 4: no motion, inner corner
  p.Line(50, 30);         // 5
  p.Line(50, 30);         // 6: no motion, outer corner
  p.Line(20, 30);         // 7
  p.G40().Line(15, 40);   // 8
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  ASSERT_EQ(run.out.size(), reference.out.size() + 3) << Csv(run.out);
  // Order: 0, 1 (unchanged), 2, 3, 4 (at the trimmed corner tip (50, 20)), 5, 6 (at the
  // shoulder's end tip (50, 29.2)), the corner arc (tag 7), 7, 8.
  const int64_t tags[] = {0, 1, 2, 3, 4, 5, 6, 7, 7, 8};
  for (size_t i = 0; i < run.out.size(); ++i) EXPECT_EQ(run.out[i].tag, tags[i]) << i;
  EXPECT_TRUE(run.out[7].inserted);
  EXPECT_TRUE(Near(run.out[1].start, {105, 25}));
  EXPECT_TRUE(Near(run.out[4].start, {50, 20}));
  EXPECT_TRUE(Near(run.out[6].start, {50, 29.2}));
  // Everything else as without them.
  const size_t map[] = {0, 2, 3, 5, 7, 8, 9};  // reference index -> index here
  for (size_t i = 0; i < reference.out.size(); ++i) {
    EXPECT_TRUE(Near(run.out[map[i]].start, reference.out[i].start)) << i;
    EXPECT_TRUE(Near(run.out[map[i]].end, reference.out[i].end)) << i;
  }
}

TEST(ToolRadiusCompensationTest, StreamingHoldsBackExactlyOneElement) {
  const Program p = OutsideDiameterAndShoulder();
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  // Popped after each push: block 0 at once, then each compensated block when the next comes.
  const size_t expected_after[] = {1, 1, 2, 3, 5, 7};
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    while (trc.Pop(e)) out.push_back(e);
    EXPECT_EQ(out.size(), expected_after[i]) << "after block " << i;
    EXPECT_EQ(trc.pending(), i >= 1 && i <= 4) << i;
    EXPECT_EQ(trc.active(), i >= 1 && i <= 4) << i;
  }
  trc.Flush();
  EXPECT_FALSE(trc.Pop(e));
  EXPECT_TRUE(CheckPath(p.blocks, out, true)) << Csv(out);
}

TEST(ToolRadiusCompensationTest, StopAtAnInnerCornerRunsBackAlongTheLastElement) {
  const Program p = OutsideDiameterAndShoulder();
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 2) trc.Flush();  // e.g. an M00 after the diameter
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error()) << trc.error()->message;
  // Not gouge-free: stopped perpendicular at the end of the diameter, the nose centre
  // (50, 20.8) stands on the line of the shoulder face, the nose overlaps it by r (the
  // shoulder was not known at the stop). Everything else holds.
  EXPECT_TRUE(CheckPath(p.blocks, out, false)) << Csv(out);
  EXPECT_NEAR(Norm(out[2].end - TipFromCentre(3, 0.8) - Vec2{50, 20.8}), 0, kTol);
  // The diameter ends perpendicular (tip (49.2, 20)), then runs back on its own offset to the
  // corner tip (50, 20), then the shoulder.
  ASSERT_EQ(out.size(), 8u) << Csv(out);
  EXPECT_TRUE(Near(out[2].end, {49.2, 20}));
  EXPECT_TRUE(out[3].inserted);
  EXPECT_EQ(out[3].tag, 3);
  EXPECT_EQ(out[3].kind, Kind::kLine);
  EXPECT_TRUE(Near(out[3].start, {49.2, 20}));
  EXPECT_TRUE(Near(out[3].end, {50, 20}));
  EXPECT_TRUE(Near(out[4].start, {50, 20}));
}

TEST(ToolRadiusCompensationTest, StopAtAnInnerCornerAfterAnArcRunsBackOnTheArc) {
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.From(-5, 15).G41().Line(-5, h);  // 0
  p.Cw(5, h, 0, 0);                  // 1
  p.Cw(15, h, 10, 0);                // 2
  p.G40().Line(20, 15);              // 3
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 1) trc.Flush();
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error()) << trc.error()->message;
  EXPECT_TRUE(CheckPath(p.blocks, out, false)) << Csv(out);  // the stop overlaps block 2
  const std::vector<ContourElement> inserted = Inserted(out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCcw);  // back along the G02
  EXPECT_TRUE(Near(inserted[0].centre, {0, 0}));
  EXPECT_TRUE(Near(inserted[0].start, {5.4, 0.54 * 2 * h}));
  EXPECT_TRUE(Near(inserted[0].end, {5, std::sqrt(10.8 * 10.8 - 25)}));
}

TEST(ToolRadiusCompensationTest, StopAtAnOuterCornerInsertsTheArcAfterwards) {
  const Program p = OutsideDiameterAndShoulder();
  const Result reference = Compensate(p.blocks);
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 3) trc.Flush();  // stop after the shoulder face: its end is perpendicular anyway
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error());
  ASSERT_EQ(out.size(), reference.out.size());
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_TRUE(Near(out[i].start, reference.out[i].start)) << i;
    EXPECT_TRUE(Near(out[i].end, reference.out[i].end)) << i;
    EXPECT_EQ(out[i].inserted, reference.out[i].inserted) << i;
  }
}

TEST(ToolRadiusCompensationTest, FlagsPassThroughAndTransitionsTakeTheNextBlocks) {
  Program p = OutsideDiameterAndShoulder();
  p.blocks[4].rapid = true;  // the block after the outer corner
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error);
  for (const ContourElement& e : run.out) {
    EXPECT_EQ(e.rapid, e.tag == 0 || e.tag == 4) << e.tag;
    EXPECT_EQ(e.nose_radius_mm, p.blocks[e.tag].nose_radius_mm);
    EXPECT_EQ(e.side, p.blocks[e.tag].side);
  }
}

TEST(ToolRadiusCompensationTest, G40ContourPassesUnchanged) {
  Program p;
  p.From(0, 0).Line(10, 0).Cw(20, 10, 10, 10).Line(20, 30).Ccw(0, 50, 0, 30);
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error);
  ASSERT_EQ(run.out.size(), p.blocks.size());
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    EXPECT_EQ(run.out[i].kind, p.blocks[i].kind);
    EXPECT_TRUE(Near(run.out[i].start, p.blocks[i].start));
    EXPECT_TRUE(Near(run.out[i].end, p.blocks[i].end));
    EXPECT_TRUE(Near(run.out[i].centre, p.blocks[i].centre));
    EXPECT_FALSE(run.out[i].inserted);
  }
}

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
