#pragma once
// Shared by the tool nose radius compensation tests (tool_radius_compensation_*_test.cpp):
// contour programs built like the NC blocks that make them, running them through the
// compensation, independent geometry, and the invariants every finished run must keep.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"

namespace vmt::control::channel::testing {

using Side = CompensationSide;
using Kind = ElementKind;

inline constexpr double kTol = 1e-9;
inline constexpr double kPi = std::numbers::pi;

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

inline Result Compensate(const std::vector<ContourElement>& in, bool flush = true) {
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
inline std::vector<ContourElement> OfTag(const std::vector<ContourElement>& out, int64_t tag) {
  std::vector<ContourElement> found;
  for (const ContourElement& e : out)
    if (e.tag == tag && !e.inserted) found.push_back(e);
  return found;
}

inline std::vector<ContourElement> Inserted(const std::vector<ContourElement>& out) {
  std::vector<ContourElement> found;
  for (const ContourElement& e : out)
    if (e.inserted) found.push_back(e);
  return found;
}

inline const char* KindName(Kind k) {
  return k == Kind::kLine ? "line" : k == Kind::kArcCw ? "G02" : "G03";
}

// CSV dump of a path for plotting a failure: kind, start, end, centre (z, x), tag, inserted.
inline std::string Csv(const std::vector<ContourElement>& path) {
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

inline std::string Str(Vec2 p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.17g, %.17g)", p.z, p.x);
  return s;
}

inline ::testing::AssertionResult Near(Vec2 actual, Vec2 expected, double tol = kTol) {
  if (std::abs(actual.z - expected.z) <= tol && std::abs(actual.x - expected.x) <= tol)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << Str(actual) << " != " << Str(expected) << " (tolerance " << tol << ")";
}

// ---------------------------------------------------------------------------------------------
// Independent geometry for the checks.

inline Vec2 Rotate(Vec2 v, double a) {
  return {v.z * std::cos(a) - v.x * std::sin(a), v.z * std::sin(a) + v.x * std::cos(a)};
}
inline Vec2 LeftOf(Vec2 v) { return {-v.x, v.z}; }
inline Vec2 UnitOf(Vec2 v) { return (1 / Norm(v)) * v; }

// Distance from a point to a line segment or to an arc (the piece between its end points).
inline double DistanceToElement(Vec2 p, const ContourElement& e) {
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
inline std::vector<Vec2> Samples(const ContourElement& e, int n = 16) {
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

inline bool IsZeroLength(const ContourElement& e) {
  return e.kind == Kind::kLine && Norm(e.end - e.start) <= kTol;
}

// What each programmed block is for the compensation, found from the modal states alone.
enum class Role { kPass, kStartUp, kCancel, kSideChange, kCompensated, kZero };

inline std::vector<Role> Roles(const std::vector<ContourElement>& in) {
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
inline ::testing::AssertionResult CheckPath(const std::vector<ContourElement>& in,
                                            const std::vector<ContourElement>& out,
                                            bool neighbours) {
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

// Rapid to the start, start-up onto the diameter 2*20, turn it towards the chuck, shoulder up
// to the diameter 2*30 (inner corner), turn that (outer corner at the shoulder edge), cancel.
inline Program OutsideDiameterAndShoulder(int edge = 3) {
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

}  // namespace vmt::control::channel::testing
