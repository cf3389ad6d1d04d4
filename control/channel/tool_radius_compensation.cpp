#include "control/channel/tool_radius_compensation.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <utility>

#include "common/demand.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLengthTolerance = 1e-9;  // mm: points closer than this coincide
constexpr double kAngleTolerance = 1e-9;   // rad: turns smaller than this are tangent
// The channel accepts arc end points this far off the circle; the compensation joins elements
// whose programmed end and start differ by at most this much.
constexpr double kContinuityTolerance = 0.01;  // mm


std::string Number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string TooShort(double r) {
  return "contour violation (gouge): the block is too short for the tool nose radius " + Number(r) +
         " mm at an inner corner, the compensated path would run backwards";
}

Vec2 Unit(Vec2 v) { return (1 / Norm(v)) * v; }
// Rotated by +90 degrees: +Z -> +X.
Vec2 Left(Vec2 v) { return {-v.x, v.z}; }
double Angle(Vec2 v) { return std::atan2(v.x, v.z); }

// Wraps an angle into [low, low + 2 pi).
double Wrap(double a, double low) {
  a = std::fmod(a - low, 2 * kPi);
  if (a < 0) a += 2 * kPi;
  return a + low;
}

bool IsArc(const ContourElement& e) { return e.kind != ElementKind::kLine; }
double Direction(const ContourElement& e) { return e.kind == ElementKind::kArcCcw ? 1 : -1; }

// Unit tangent of the programmed element at a point on it, in the direction of motion.
Vec2 TangentAt(const ContourElement& e, Vec2 p) {
  if (!IsArc(e)) return Unit(e.end - e.start);
  const Vec2 radial = Unit(p - e.centre);
  return Direction(e) * Left(radial);
}

// The offset curve an element's nose centre runs on: a line (through `point`, along `dir`) or a
// circle (around `point`, radius `radius`).
struct Curve {
  bool circle = false;
  Vec2 point, dir;
  double radius = 0;
};

Curve CurveOf(const OffsetElement& a) {
  if (IsArc(a.block) && !a.start_up) return {true, a.block.centre, {}, a.offset_radius};
  return {false, a.q1, TangentAt(a.block, a.block.end), 0};
}

// Intersections of two offset curves (0, 1 or 2 points); touching within the tolerance counts.
int Intersect(const Curve& a, const Curve& b, Vec2 (&out)[2]) {
  if (!a.circle && !b.circle) {
    const double denominator = Cross(a.dir, b.dir);
    if (std::abs(denominator) < 1e-15) return 0;
    const double t = Cross(b.point - a.point, b.dir) / denominator;
    out[0] = a.point + t * a.dir;
    return 1;
  }
  if (a.circle != b.circle) {
    const Curve& line = a.circle ? b : a;
    const Curve& circle = a.circle ? a : b;
    const Vec2 foot = line.point + Dot(circle.point - line.point, line.dir) * line.dir;
    const double h = Norm(circle.point - foot);
    if (h > circle.radius + kLengthTolerance) return 0;
    const double t = std::sqrt(std::max(0.0, circle.radius * circle.radius - h * h));
    out[0] = foot + t * line.dir;
    out[1] = foot - t * line.dir;
    return 2;
  }
  const Vec2 between = b.point - a.point;
  const double d = Norm(between);
  if (d < 1e-12) return 0;
  if (d > a.radius + b.radius + kLengthTolerance ||
      d < std::abs(a.radius - b.radius) - kLengthTolerance)
    return 0;
  const Vec2 u = (1 / d) * between;
  const double along = (a.radius * a.radius - b.radius * b.radius + d * d) / (2 * d);
  const double h = std::sqrt(std::max(0.0, a.radius * a.radius - along * along));
  const Vec2 base = a.point + along * u;
  out[0] = base + h * Left(u);
  out[1] = base - h * Left(u);
  return 2;
}

// Position of the trimmed ends on a compensated arc, as angles travelled from the programmed
// start: u0 for q0, u1 for q1. Trims at the start move forwards, trims at the end backwards.
void ArcTravel(const OffsetElement& a, double& u0, double& u1) {
  const double sigma = Direction(a.block);
  const Vec2 c = a.block.centre;
  u0 = Wrap(sigma * (Angle(a.q0 - c) - Angle(a.block.start - c)), -kPi / 2);
  const double back = Wrap(sigma * (Angle(a.block.end - c) - Angle(a.q1 - c)), -kPi / 2);
  u1 = std::abs(a.sweep) - back;
}

// Whether a point of an element's offset curve lies between its (current) start and end.
bool OnOffset(const OffsetElement& a, Vec2 x) {
  if (!IsArc(a.block)) {
    const Vec2 d = TangentAt(a.block, a.block.end);
    const double t = Dot(x - a.q0, d);
    return t >= -kLengthTolerance && t <= Dot(a.q1 - a.q0, d) + kLengthTolerance;
  }
  double u0, u1;
  ArcTravel(a, u0, u1);
  const double tolerance = kLengthTolerance / a.offset_radius;
  const Vec2 c = a.block.centre;
  const double u = Wrap(Direction(a.block) * (Angle(x - c) - Angle(a.q0 - c)), -tolerance);
  return u <= u1 - u0 + tolerance;
}

// An arc of the tip path; a piece shorter than the length tolerance becomes a line (the
// channel would take an arc with start == end for a full circle).
ContourElement ArcOrLine(ContourElement e, double travelled) {
  if (Norm(e.end - e.start) <= kLengthTolerance && std::abs(travelled) < kPi)
    e.kind = ElementKind::kLine;
  return e;
}

}  // namespace

double Norm(Vec2 a) { return std::hypot(a.z, a.x); }

Vec2 TipFromCentre(int edge_position, double r) {
  switch (edge_position) {
    case 1:
      return {r, r};
    case 2:
      return {-r, r};
    case 3:
      return {-r, -r};
    case 4:
      return {r, -r};
    case 5:
      return {0, r};
    case 6:
      return {-r, 0};
    case 7:
      return {0, -r};
    case 8:
      return {r, 0};
    default:
      return {0, 0};
  }
}

double ArcSweep(const ContourElement& arc) {
  if (!IsArc(arc)) return 0;
  const double sigma = Direction(arc);
  if (Norm(arc.end - arc.start) <= kLengthTolerance) return sigma * 2 * kPi;
  const double turn = Angle(arc.end - arc.centre) - Angle(arc.start - arc.centre);
  // Counter-clockwise in (0, 2 pi), clockwise in (-2 pi, 0).
  return sigma * Wrap(sigma * turn, 0);
}

void ToolRadiusCompensation::Reset() { *this = ToolRadiusCompensation(); }

bool ToolRadiusCompensation::Pop(ContourElement& out) {
  if (out_.empty()) return false;
  out = out_.front();
  out_.pop_front();
  return true;
}

void ToolRadiusCompensation::Fail(int64_t tag, std::string message) {
  error_ = CompensationError{tag, std::move(message)};
  pending_.reset();
  deferred_.clear();
  last_.reset();
}

void ToolRadiusCompensation::Push(const ContourElement& e) {
  if (error_) return;
  if (e.side != CompensationSide::kOff) {
    if (e.edge_position < 0 || e.edge_position > 9)
      return Fail(e.tag,
                  "invalid cutting edge position " + std::to_string(e.edge_position) + " (0..9)");
    if (!(e.nose_radius_mm >= 0))
      return Fail(e.tag, "negative tool nose radius " + Number(e.nose_radius_mm) + " mm");
  }
  if (!IsArc(e) && Norm(e.end - e.start) <= kLengthTolerance) return ZeroLength(e);
  if (!active_) {
    if (e.side == CompensationSide::kOff) {
      out_.push_back(e);
      return;
    }
    return StartUp(e, false);
  }
  if (e.side == CompensationSide::kOff) return Cancel(e);
  if (e.side != side_) return StartUp(e, true);
  return Continue(e);
}

void ToolRadiusCompensation::ZeroLength(const ContourElement& e) {
  // A block without motion in the plane keeps its place: it comes out where the tip is then.
  if (pending_) {
    deferred_.push_back(e);
    return;
  }
  ContourElement still = e;
  if (active_) still.start = still.end = TipNow();
  out_.push_back(still);
}

Vec2 ToolRadiusCompensation::ProgrammedEnd() const {
  VMT_DEMAND(pending_ || last_, "ToolRadiusCompensation: no compensated element before this one");
  return pending_ ? pending_->block.end : last_->block.end;
}

Vec2 ToolRadiusCompensation::TipNow() const {
  VMT_DEMAND(!pending_ && last_,
             "ToolRadiusCompensation: tip point asked for while an element is held back");
  return last_->q1 + last_->tip;
}

bool ToolRadiusCompensation::CheckContinuity(const ContourElement& e) {
  const double gap = Norm(e.start - ProgrammedEnd());
  if (gap <= kContinuityTolerance) return true;
  Fail(e.tag, "contour not continuous under G41/G42: the block starts " + Number(gap) +
                  " mm away from the previous end point");
  return false;
}

void ToolRadiusCompensation::StartUp(const ContourElement& e, bool side_change) {
  if (IsArc(e)) {
    if (side_change)
      return Fail(e.tag,
                  "G41/G42 side change on an arc: the block that changes the compensation side "
                  "must be a straight line (G00/G01)");
    return Fail(e.tag,
                "G41/G42 start-up on an arc: the block that starts tool nose radius compensation "
                "must be a straight line (G00/G01)");
  }
  Vec2 start = e.start, from = e.start;
  if (side_change) {
    // Cancel and start-up in one block: the old side ends perpendicular at its end point.
    if (!CheckContinuity(e)) return;
    start = ProgrammedEnd();
    if (Norm(e.end - start) <= kLengthTolerance) return ZeroLength(e);
    if (!FinishPending()) return;
    from = TipNow();
  }
  side_ = e.side;
  r_ = e.nose_radius_mm;
  edge_ = e.edge_position;
  OffsetElement o;
  if (!MakeOffset(e, start, o)) return;
  o.start_up = true;
  o.start_up_from = from;
  pending_ = o;
  last_.reset();
  active_ = true;
}

void ToolRadiusCompensation::Cancel(const ContourElement& e) {
  if (IsArc(e))
    return Fail(e.tag,
                "G40 cancel on an arc: the block that cancels tool nose radius compensation must "
                "be a straight line (G00/G01)");
  if (!CheckContinuity(e)) return;
  if (!FinishPending()) return;
  ContourElement cancel = e;
  cancel.start = TipNow();
  out_.push_back(cancel);
  active_ = false;
  side_ = CompensationSide::kOff;
  last_.reset();
}

void ToolRadiusCompensation::Continue(const ContourElement& e) {
  if (std::abs(e.nose_radius_mm - r_) > 1e-12)
    return Fail(e.tag, "tool nose radius changed while G41/G42 is active (r " + Number(r_) +
                           " -> " + Number(e.nose_radius_mm) + " mm): cancel with G40 first");
  if (e.edge_position != edge_)
    return Fail(e.tag, "cutting edge position changed while G41/G42 is active (" +
                           std::to_string(edge_) + " -> " + std::to_string(e.edge_position) +
                           "): cancel with G40 first");
  if (!CheckContinuity(e)) return;
  const Vec2 start = ProgrammedEnd();
  if (!IsArc(e) && Norm(e.end - start) <= kLengthTolerance) return ZeroLength(e);
  OffsetElement b;
  if (!MakeOffset(e, start, b)) return;
  std::vector<ContourElement> inserted;
  if (pending_) {
    if (!Corner(*pending_, b, false, inserted)) return;
    if (!RunsForward(*pending_) || !NoLoop(*pending_, b)) return;
    if (!FinishPending()) return;
  } else {
    if (!Corner(*last_, b, true, inserted) || !NoLoop(*last_, b)) return;
  }
  for (const ContourElement& i : inserted) out_.push_back(i);
  pending_ = b;
}

void ToolRadiusCompensation::Flush() {
  if (error_) return;
  FinishPending();
}

bool ToolRadiusCompensation::MakeOffset(const ContourElement& e, Vec2 start, OffsetElement& o) {
  o.block = e;
  o.block.start = start;
  o.s = e.side == CompensationSide::kLeft ? 1 : -1;
  o.tip = TipFromCentre(e.edge_position, e.nose_radius_mm);
  const double r = e.nose_radius_mm;
  if (!IsArc(e)) {
    const Vec2 n = o.s * Left(Unit(e.end - start));
    o.q0 = start + r * n;
    o.q1 = e.end + r * n;
    return true;
  }
  const Vec2 c = e.centre;
  const double radius = Norm(start - c);
  if (radius <= kLengthTolerance || Norm(e.end - c) <= kLengthTolerance) {
    Fail(e.tag, radius <= kLengthTolerance ? "arc centre on the arc start point"
                                           : "arc centre on the arc end point");
    return false;
  }
  // The arc's radius is taken at its start; the end point is put on that circle (as the
  // channel interpolates it). A full circle stays one.
  if (Norm(e.end - e.start) <= kLengthTolerance)
    o.block.end = start;
  else
    o.block.end = c + radius * Unit(e.end - c);
  o.sweep = ArcSweep(o.block);
  const double offset_radius = radius - Direction(e) * o.s * r;
  if (offset_radius < -kLengthTolerance) {
    Fail(e.tag, "arc radius " + Number(radius) + " mm smaller than the tool nose radius " +
                    Number(r) + " mm on the inner side of the arc");
    return false;
  }
  o.offset_radius = std::max(0.0, offset_radius);
  o.q0 = c + o.offset_radius * Unit(start - c);
  o.q1 = c + o.offset_radius * Unit(o.block.end - c);
  return true;
}

bool ToolRadiusCompensation::Corner(OffsetElement& a, OffsetElement& b, bool a_emitted,
                                    std::vector<ContourElement>& inserted) {
  // The start-up line ends perpendicular to the element after it: no corner.
  if (a.start_up && !a_emitted) {
    a.q1 = b.q0;
    return true;
  }
  const Vec2 corner = b.block.start;
  const Vec2 t_a = TangentAt(a.block, a.block.end);
  const Vec2 t_b = TangentAt(b.block, corner);
  const double turn = std::atan2(Cross(t_a, t_b), Dot(t_a, t_b));  // > 0: turns left
  if (Norm(b.q0 - a.q1) <= kLengthTolerance || std::abs(turn) <= kAngleTolerance) {
    b.q0 = a.q1;
    return true;
  }
  ContourElement element = b.block;
  element.inserted = true;
  const bool inner = a.s * turn > 0 && kPi - std::abs(turn) > kAngleTolerance;
  if (!inner) {
    // Around the corner point on a circle of the nose radius: clockwise with the tool on the
    // left (the contour turns right), counter-clockwise with the tool on the right.
    element.kind = a.s > 0 ? ElementKind::kArcCw : ElementKind::kArcCcw;
    element.start = a.q1 + a.tip;
    element.end = b.q0 + a.tip;
    element.centre = corner + a.tip;
    inserted.push_back(ArcOrLine(element, turn));
    return true;
  }
  // Inner corner: both offset curves end at their intersection nearest to the corner.
  Vec2 points[2];
  const int n = Intersect(CurveOf(a), CurveOf(b), points);
  if (n == 0) {
    Fail(b.block.tag,
         "contour violation (gouge): the offset contour has no intersection at the inner "
         "corner, the tool nose radius " +
             Number(b.block.nose_radius_mm) + " mm does not fit");
    return false;
  }
  Vec2 meet = points[0];
  if (n == 2 && Norm(points[1] - corner) < Norm(points[0] - corner)) meet = points[1];
  if (!a_emitted) {
    a.q1 = meet;
    b.q0 = meet;
    return true;
  }
  // After a stop the last element already ends perpendicular at its end: run back along its
  // offset curve to the intersection (on that curve, so the contour is not cut).
  double back = 0, available = 0;
  const bool on_arc = IsArc(a.block) && !a.start_up;
  if (on_arc) {
    double u0, u1;
    ArcTravel(a, u0, u1);
    const Vec2 c = a.block.centre;
    back =
        Wrap(Direction(a.block) * (Angle(a.q1 - c) - Angle(meet - c)), -kPi / 2) * a.offset_radius;
    available = (u1 - u0) * a.offset_radius;
  } else {
    back = Dot(a.q1 - meet, t_a);
    available = a.start_up ? Norm(a.block.end - a.block.start) : Dot(a.q1 - a.q0, t_a);
  }
  if (back > available + kLengthTolerance || back < -kLengthTolerance) {
    Fail(a.block.tag, TooShort(a.block.nose_radius_mm));
    return false;
  }
  b.q0 = meet;
  if (Norm(meet - a.q1) <= kLengthTolerance) {
    b.q0 = a.q1;
    return true;
  }
  element.kind = ElementKind::kLine;
  element.start = a.q1 + a.tip;
  element.end = meet + a.tip;
  if (on_arc) {
    element.kind =
        a.block.kind == ElementKind::kArcCcw ? ElementKind::kArcCw : ElementKind::kArcCcw;
    element.centre = a.block.centre + a.tip;
    element = ArcOrLine(element, back / a.offset_radius);
  }
  inserted.push_back(element);
  return true;
}

bool ToolRadiusCompensation::RunsForward(const OffsetElement& a) {
  if (a.start_up) return true;
  double travel = 0;
  if (!IsArc(a.block)) {
    travel = Dot(a.q1 - a.q0, TangentAt(a.block, a.block.end));
  } else if (a.offset_radius > kLengthTolerance) {
    double u0, u1;
    ArcTravel(a, u0, u1);
    travel = (u1 - u0) * a.offset_radius;
  }
  if (travel >= -kLengthTolerance) return true;
  Fail(a.block.tag, TooShort(a.block.nose_radius_mm));
  return false;
}

bool ToolRadiusCompensation::NoLoop(const OffsetElement& a, const OffsetElement& b) {
  if (a.start_up || (IsArc(a.block) && a.offset_radius <= kLengthTolerance) ||
      (IsArc(b.block) && b.offset_radius <= kLengthTolerance))
    return true;
  // Where the offset curves meet other than at the joint (up to the loop size worth telling).
  constexpr double kJoint = 1e-6;  // mm
  Vec2 points[2];
  const int n = Intersect(CurveOf(a), CurveOf(b), points);
  for (int i = 0; i < n; ++i) {
    const Vec2 x = points[i];
    if (Norm(x - a.q1) <= kJoint || Norm(x - b.q0) <= kJoint) continue;
    if (OnOffset(a, x) && OnOffset(b, x)) {
      Fail(b.block.tag,
           "contour violation (gouge): the compensated path of the block crosses that of the "
           "block before, the contour comes back within the tool nose radius " +
               Number(b.block.nose_radius_mm) + " mm");
      return false;
    }
  }
  return true;
}

bool ToolRadiusCompensation::Emit(const OffsetElement& a) {
  if (!RunsForward(a)) return false;
  ContourElement out = a.block;
  out.start = a.q0 + a.tip;
  out.end = a.q1 + a.tip;
  if (a.start_up) {
    out.start = a.start_up_from;
  } else if (IsArc(a.block) && a.offset_radius <= kLengthTolerance) {
    // Arc radius == nose radius on the inner side: the nose centre stands on the arc centre.
    out.kind = ElementKind::kLine;
    out.start = out.end = a.block.centre + a.tip;
  } else if (IsArc(a.block)) {
    double u0, u1;
    ArcTravel(a, u0, u1);
    out.centre = a.block.centre + a.tip;
    out = ArcOrLine(out, u1 - u0);
  }
  out_.push_back(out);
  last_ = a;
  return true;
}

bool ToolRadiusCompensation::FinishPending() {
  if (!pending_) return true;
  const OffsetElement a = *pending_;
  pending_.reset();
  if (!Emit(a)) return false;
  for (ContourElement still : deferred_) {
    still.start = still.end = a.q1 + a.tip;
    out_.push_back(still);
  }
  deferred_.clear();
  return true;
}

}  // namespace vmt::control::channel
