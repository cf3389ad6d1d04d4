#include "control/channel/block_motion.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {
namespace {

// Plane axes (first, second) by address: G17 X-Y, G18 Z-X, G19 Y-Z; the arc turns
// counter-clockwise from first to second.
void PlaneAxes(nc::Plane plane, const char*& first, const char*& second, char& i_first,
               char& i_second) {
  if (plane == nc::Plane::kXY)
    first = "X", second = "Y", i_first = 'I', i_second = 'J';
  else if (plane == nc::Plane::kYZ)
    first = "Y", second = "Z", i_first = 'J', i_second = 'K';
  else
    first = "Z", second = "X", i_first = 'K', i_second = 'I';
}

double Length(const BlockMotion& m) {
  // |dP/du| in axis space: a line's and a helix's are constant.
  double sum = 0;
  for (size_t a = 0; a < m.end.size(); ++a) {
    if (static_cast<int>(a) == m.arc_axes[0] || static_cast<int>(a) == m.arc_axes[1]) continue;
    sum += (m.end[a] - m.start[a]) * (m.end[a] - m.start[a]);
  }
  if (m.arc_axes[0] >= 0) sum += std::pow(m.arc_radius * m.arc_sweep, 2);
  return std::max(std::sqrt(sum), 1e-12);
}

// G31: a straight line or (G02/G03) an arc of the face plane (coordinate_transformation.hpp).
// The path feed (F, or G00 at X's rapid) is limited so that C keeps its rapid rate and
// acceleration and X its acceleration where the path passes the centre closest: dC/dt = v th',
// d2C/dt2 = a th' + v^2 th'', d2X/dt2 <= a + v^2 r'' (the bounds of th', th'', r'' of a line or
// an arc in the header). Half of each axis' acceleration goes to each term.
std::optional<MotionError> PlanFaceMotion(const nc::PreparedBlock& block,
                                          const std::vector<double>& start,
                                          const std::vector<double>& translation,
                                          const std::vector<axes::AxisParameters>& axes,
                                          BlockMotion& out, uint64_t follow_up) {
  int x = -1, c = -1;
  for (size_t a = 0; a < axes.size(); ++a) {
    if (axes[a].name == "X") x = static_cast<int>(a);
    if (axes[a].name == "C") c = static_cast<int>(a);
  }
  if (x < 0 || c < 0)
    return MotionError{"G31 needs the axes X and C in this channel", kMsgTransformation};
  // The NC positions C only in rotary axis mode (C-axis manual 4.3); X1/Y1 do not select it.
  if (follow_up >> c & 1)
    return MotionError{"G31 (face transformation) needs the headstock in rotary axis mode: "
                       "select it (G00 C..) before X1/Y1",
                       kMsgTransformation};
  const bool arc = block.motion == nc::Motion::kArcCw || block.motion == nc::Motion::kArcCcw;
  if (block.motion != nc::Motion::kRapid && block.motion != nc::Motion::kLinear && !arc)
    return MotionError{"G31 (face transformation) moves X1/Y1 with G00, G01, G02 or G03 only",
                       kMsgTransformation};
  out.face_axes[0] = x, out.face_axes[1] = c;
  out.face_shift[0] = translation[x], out.face_shift[1] = translation[c];
  out.face_from = nc::MachineToFace(start[x] - translation[x], start[c] - translation[c]);
  out.face_to = nc::MachineToFace(out.end[x] - translation[x], out.end[c] - translation[c]);
  if (arc) {
    // The interpreter made C's target from the same words (I/J relative to the start, or R).
    std::string error;
    out.face_arc =
        nc::FaceArcOf(out.face_from, out.face_to, block.motion == nc::Motion::kArcCw,
                      block.has_centre, block.centre[0], block.centre[1], block.radius, error);
    if (!error.empty()) return MotionError{"G31 G02/G03: " + error, kMsgArcGeometry};
    out.face_is_arc = true;
  }
  const nc::FaceLine line = out.FaceBounds();
  if (arc && line.through_centre) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "G31: the arc X1 %.4f Y1 %.4f -> X1 %.4f Y1 %.4f (centre X1 %.4f Y1 %.4f) "
                  "passes the centre of the face, where C is undefined: program it around the "
                  "centre",
                  out.face_from.x1, out.face_from.y1, out.face_to.x1, out.face_to.y1,
                  out.face_arc.centre.x1, out.face_arc.centre.y1);
    return MotionError{text, kMsgTransformation};
  }
  if (line.through_centre && line.length > 1e-9) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "G31: the line X1 %.4f Y1 %.4f -> X1 %.4f Y1 %.4f passes the centre of the "
                  "face, where C is undefined: program it in two moves around the centre",
                  out.face_from.x1, out.face_from.y1, out.face_to.x1, out.face_to.y1);
    return MotionError{text, kMsgTransformation};
  }
  // The other linear axes (Z) follow linearly along u; the path counts them with the line.
  double other2 = 0;
  double rapid = axes[x].rapid_per_s, accel = axes[x].acceleration;
  double jerk = axes[x].jerk > 0 ? axes[x].jerk : HUGE_VAL;
  for (size_t a = 0; a < axes.size(); ++a) {
    if (static_cast<int>(a) == x || static_cast<int>(a) == c) continue;
    const double delta = out.end[a] - start[a];
    if (std::abs(delta) < 1e-12) continue;
    other2 += delta * delta;
    rapid = std::min(rapid, axes[a].rapid_per_s);
    accel = std::min(accel, axes[a].acceleration);
    if (axes[a].jerk > 0) jerk = std::min(jerk, axes[a].jerk);
  }
  const double length = std::sqrt(line.length * line.length + other2);
  double feed = block.motion == nc::Motion::kRapid ? rapid : block.modal.feed / 60.0;
  if (block.motion != nc::Motion::kRapid && feed <= 0)
    return MotionError{"no feed programmed (F)", kMsgNoFeed};
  const double deg = 180 / std::numbers::pi;
  double path_accel = accel / 2;
  if (line.theta_s_max > 0) {
    feed = std::min(feed, axes[c].rapid_per_s / deg / line.theta_s_max);
    path_accel = std::min(path_accel, axes[c].acceleration / deg / 2 / line.theta_s_max);
  }
  if (line.theta_ss_max > 0)
    feed = std::min(feed, std::sqrt(axes[c].acceleration / deg / 2 / line.theta_ss_max));
  if (line.r_ss_max > 0) feed = std::min(feed, std::sqrt(axes[x].acceleration / 2 / line.r_ss_max));
  feed = std::min(feed, rapid);
  out.max_rate = feed / length;
  out.max_accel = path_accel / length;
  // Jerk: the linear axes' (C's third derivative near the centre is bounded by the feed and
  // acceleration limits above only).
  out.max_jerk = std::isfinite(jerk) ? jerk / length : 0;
  out.length = length;
  out.moves = true;
  return std::nullopt;
}

}  // namespace

nc::FictivePoint BlockMotion::FacePoint(double u) const {
  if (face_is_arc) return face_arc.At(u);
  return {face_from.x1 + (face_to.x1 - face_from.x1) * u,
          face_from.y1 + (face_to.y1 - face_from.y1) * u};
}

nc::FaceLine BlockMotion::FaceBounds() const {
  return face_is_arc ? nc::FaceArcBoundsOf(face_arc) : nc::FaceLineOf(face_from, face_to);
}

void BlockMotion::PointAt(double u, std::vector<double>& out) const {
  out.resize(start.size());
  for (size_t a = 0; a < start.size(); ++a) out[a] = start[a] + (end[a] - start[a]) * u;
  if (arc_axes[0] >= 0) {
    const double angle = arc_start_angle + arc_sweep * u;
    out[arc_axes[0]] = arc_centre[0] + arc_radius * std::cos(angle);
    out[arc_axes[1]] = arc_centre[1] + arc_radius * std::sin(angle);
  }
  if (face_axes[0] >= 0) {
    // G31: the point of the fictive line or arc, transformed. C's sweep from the start is
    // continuous along a path that misses the centre (planning refused the others): a line's
    // is less than 180 deg, an arc's is unwound piece by piece.
    const nc::FictivePoint p = FacePoint(u);
    out[face_axes[0]] = std::hypot(p.x1, p.y1) + face_shift[0];
    const double sweep =
        face_is_arc ? nc::FaceArcSweepDeg(face_arc, u) : nc::SweepDeg(face_from, p);
    out[face_axes[1]] = u >= 1 ? end[face_axes[1]] : start[face_axes[1]] + sweep;
  }
}

std::vector<double> BlockMotion::Direction(double u) const {
  std::vector<double> d(start.size());
  for (size_t a = 0; a < start.size(); ++a) d[a] = end[a] - start[a];
  if (arc_axes[0] >= 0) {
    const double angle = arc_start_angle + arc_sweep * u;
    d[arc_axes[0]] = -arc_radius * arc_sweep * std::sin(angle);
    d[arc_axes[1]] = arc_radius * arc_sweep * std::cos(angle);
  }
  if (face_axes[0] >= 0) {
    // G31: dX/du = (p . dp) / r, dC/du = (p x dp) / r^2 (rad -> deg).
    const nc::FictivePoint tangent =
        face_is_arc ? face_arc.Tangent(u)
                    : nc::FictivePoint{face_to.x1 - face_from.x1, face_to.y1 - face_from.y1};
    const double dx = tangent.x1, dy = tangent.y1;
    const nc::FictivePoint p = FacePoint(u);
    const double px = p.x1, py = p.y1;
    const double r2 = std::max(px * px + py * py, 1e-18);
    d[face_axes[0]] = (px * dx + py * dy) / std::sqrt(r2);
    d[face_axes[1]] = (px * dy - py * dx) / r2 * 180 / std::numbers::pi;
  }
  return d;
}

namespace {

// A feed move's limits along a straight path (not G00): path feed, acceleration and
// jerk. `axis_rate` is the least rapid rate over the axes that move.
void PlanStraightFeed(const nc::PreparedBlock& block, const std::vector<double>& delta,
                      const std::vector<axes::AxisParameters>& axes, double feed, double axis_rate,
                      BlockMotion& out) {
  const size_t n = axes.size();
  // Feed moves accelerate along the path at the least limit of the linear axes that move,
  // whatever the direction, so that the look-ahead sees the same limits in every block of a
  // contour (look_ahead.hpp); each axis stays within its own limit, as its share of the path
  // is at most 1. Rotary axes keep their own share.
  double span2 = 0;
  for (size_t a = 0; a < n; ++a) span2 += delta[a] * delta[a];
  const double span = std::sqrt(span2);
  double path_accel = std::numeric_limits<double>::infinity();
  double path_jerk = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < n; ++a) {
    if (std::abs(delta[a]) < 1e-12) continue;
    const double share = axes[a].rotary ? std::abs(delta[a]) : span;
    path_accel = std::min(path_accel, axes[a].acceleration / share);
    if (axes[a].jerk > 0) path_jerk = std::min(path_jerk, axes[a].jerk / share);
  }
  out.max_jerk = std::isfinite(path_jerk) ? path_jerk : 0;
  // Path length over the linear axes; a rotary axis counts with its effective distance
  // (C-axis manual 1.2: RX, RY, RZ, the tool contact point's position vector, constant over
  // the block): the tool moves at the rotation times the vector's distance from the rotation
  // axis (A about X, B about Y, C about Z). Without effective distances a rotary axis counts
  // alone, in degrees.
  double length2 = 0, rotary2 = 0;
  for (size_t a = 0; a < n; ++a) {
    if (!axes[a].rotary) {
      length2 += delta[a] * delta[a];
      continue;
    }
    const char about = axes[a].name.empty() ? 'C' : axes[a].name[0];
    const int along = about == 'A' ? 0 : about == 'B' ? 1 : 2;
    double radius2 = 0;
    bool effective = false;
    for (int k = 0; k < 3; ++k) {
      if (k == along || !(block.has_effective_distance >> k & 1)) continue;
      effective = true;
      radius2 += block.effective_distance[k] * block.effective_distance[k];
    }
    if (effective)
      length2 += radius2 * std::pow(delta[a] * std::numbers::pi / 180, 2);
    else
      rotary2 += delta[a] * delta[a];
  }
  const double length = std::sqrt(length2 > 0 ? length2 : rotary2);
  out.max_rate = std::min(feed / length, axis_rate);
  out.max_accel = path_accel;
}

// G02/G03 in the block's plane: centre from I/J/K or R, radius, sweep, and its limits.
std::optional<MotionError> PlanArc(const nc::PreparedBlock& block, const std::vector<double>& start,
                                   const std::vector<axes::AxisParameters>& axes, double feed,
                                   BlockMotion& out) {
  const size_t n = axes.size();
  const char *first, *second;
  char i_first, i_second;
  PlaneAxes(block.modal.plane, first, second, i_first, i_second);
  for (size_t a = 0; a < n; ++a) {
    if (axes[a].name == first) out.arc_axes[0] = static_cast<int>(a);
    if (axes[a].name == second) out.arc_axes[1] = static_cast<int>(a);
  }
  if (out.arc_axes[0] < 0 || out.arc_axes[1] < 0)
    return MotionError{std::string("the arc plane G") +
                           std::to_string(nc::GCode(block.modal.plane)) + " needs axes " + first +
                           " and " + second,
                       kMsgArcPlane};
  const int a0 = out.arc_axes[0], a1 = out.arc_axes[1];
  const double s0 = start[a0], s1 = start[a1], e0 = out.end[a0], e1 = out.end[a1];
  const bool cw = block.motion == nc::Motion::kArcCw;
  double c0, c1;
  if (block.has_centre) {
    c0 = s0 + block.centre[i_first - 'I'];
    c1 = s1 + block.centre[i_second - 'I'];
  } else if (block.radius != 0) {
    // Centre from R: on the chord's bisector; R < 0 picks the arc over 180 degrees.
    const double dx = e0 - s0, dy = e1 - s1, chord = std::hypot(dx, dy);
    const double r = std::abs(block.radius);
    if (chord < 1e-12 || chord > 2 * r + kArcTolerance)
      return MotionError{"radius R too small for the end point", kMsgArcGeometry};
    const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
    const double side = ((block.radius > 0) == cw) ? -1 : 1;
    c0 = (s0 + e0) / 2 - side * h * dy / chord;
    c1 = (s1 + e1) / 2 + side * h * dx / chord;
  } else {
    return MotionError{"G02/G03 needs a centre (I/J/K) or a radius R", kMsgArcGeometry};
  }
  const double r_start = std::hypot(s0 - c0, s1 - c1), r_end = std::hypot(e0 - c0, e1 - c1);
  if (std::abs(r_start - r_end) > kArcTolerance || r_start < 1e-9)
    return MotionError{"end point not on the arc (radius " + std::to_string(r_start) +
                           " at the start, " + std::to_string(r_end) + " at the end)",
                       kMsgArcGeometry};
  out.arc_centre[0] = c0;
  out.arc_centre[1] = c1;
  out.arc_radius = r_start;
  out.arc_start_angle = std::atan2(s1 - c1, s0 - c0);
  double sweep = std::atan2(e1 - c1, e0 - c0) - out.arc_start_angle;
  if (cw) {
    while (sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
  } else {
    while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
  }
  if (std::abs(std::abs(sweep) - 2 * std::numbers::pi) < 1e-9 &&
      std::hypot(e0 - s0, e1 - s1) > 1e-9)
    sweep = std::fmod(sweep, 2 * std::numbers::pi);
  out.arc_sweep = sweep;
  const double length = out.arc_radius * std::abs(sweep);
  const double accel = std::min(axes[a0].acceleration, axes[a1].acceleration);
  // Centripetal acceleration v^2/r must stay within the axes' limit too.
  const double v = std::min(feed, std::sqrt(accel * out.arc_radius));
  out.max_rate = v / length;
  out.max_accel = accel / length;
  const double jerk = std::min(axes[a0].jerk > 0 ? axes[a0].jerk : HUGE_VAL,
                               axes[a1].jerk > 0 ? axes[a1].jerk : HUGE_VAL);
  out.max_jerk = std::isfinite(jerk) ? jerk / length : 0;
  return std::nullopt;
}

}  // namespace

std::optional<MotionError> PlanBlockMotion(const nc::PreparedBlock& block,
                                           const std::vector<double>& start,
                                           const std::vector<double>& translation,
                                           const std::vector<axes::AxisParameters>& axes,
                                           double spindle_rev_per_s, BlockMotion& out,
                                           uint64_t follow_up) {
  out = BlockMotion{};
  out.start = start;
  out.end = block.target;
  const size_t n = axes.size();
  for (size_t a = 0; a < n; ++a) {
    if (follow_up >> a & 1) {
      out.end[a] = start[a];
      continue;
    }
    out.end[a] += translation[a];
    const axes::AxisParameters& axis = axes[a];
    if (axis.travel_max > axis.travel_min &&
        (out.end[a] < axis.travel_min - 1e-9 || out.end[a] > axis.travel_max + 1e-9)) {
      char text[160];
      std::snprintf(text, sizeof text, "axis %s target %.4f is beyond its travel %.4f .. %.4f",
                    axis.name.c_str(), out.end[a], axis.travel_min, axis.travel_max);
      return MotionError{text, kMsgSoftwareLimit};
    }
  }
  std::vector<double> delta(n);
  double max_delta = 0;
  for (size_t a = 0; a < n; ++a)
    max_delta = std::max(max_delta, std::abs(delta[a] = out.end[a] - start[a]));
  const bool arc = block.motion == nc::Motion::kArcCw || block.motion == nc::Motion::kArcCcw;
  if (max_delta < 1e-12 && !arc) return std::nullopt;
  if (block.fictive && block.modal.transformation == nc::Transformation::kFace)
    return PlanFaceMotion(block, start, translation, axes, out, follow_up);

  // Per-axis limits on du/dt and d2u/dt2 for a straight move in axis space.
  double axis_rate = std::numeric_limits<double>::infinity();
  double axis_accel = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < n; ++a) {
    if (std::abs(delta[a]) < 1e-12) continue;
    axis_rate = std::min(axis_rate, axes[a].rapid_per_s / std::abs(delta[a]));
    axis_accel = std::min(axis_accel, axes[a].acceleration / std::abs(delta[a]));
  }

  // Path feed, mm/s: F mm/min, or mm/rev times the spindle speed (G95).
  double feed = block.modal.feed / 60.0;
  if (block.modal.feed_per_revolution) feed = block.modal.feed * std::abs(spindle_rev_per_s);
  if (block.motion != nc::Motion::kRapid && feed <= 0)
    return MotionError{"no feed programmed (F)", kMsgNoFeed};

  // Jerk: the axes' limit, as for the acceleration (0: not limited).
  double axis_jerk = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < n; ++a)
    if (std::abs(delta[a]) >= 1e-12 && axes[a].jerk > 0)
      axis_jerk = std::min(axis_jerk, axes[a].jerk / std::abs(delta[a]));
  if (std::isfinite(axis_jerk)) out.max_jerk = axis_jerk;
  if (block.motion == nc::Motion::kRapid) {
    out.max_rate = axis_rate;
    out.max_accel = axis_accel;
  } else if (!arc) {
    PlanStraightFeed(block, delta, axes, feed, axis_rate, out);
  } else {
    if (std::optional<MotionError> e = PlanArc(block, start, axes, feed, out)) return e;
  }
  out.length = Length(out);
  out.moves = true;
  return std::nullopt;
}

}  // namespace vmt::control::channel
