#pragma once
// The coordinate transformations of G group 17 (REPOS manual 5.2, 8.3: G(17) = 31 "coord.
// transformation active"): pure geometry between the fictive Cartesian axes X1, Y1 and the
// machine axes X (radius, mm) and C (deg). The manuals name the transformation but not its
// geometry; vmt's, as MTC200-style lathe controls offer it:
//  - G31 face (end-face) transformation: X1, Y1 Cartesian in the face plane, origin on the
//    spindle axis. X = sqrt(X1^2 + Y1^2), C = atan2(Y1, X1) (C counter-clockwise from X1 to Y1).
//  - G32 cylinder surface transformation: X1 is X, Y1 the arc length on the cylinder of radius
//    r (X when G32 became active): C = Y1 / r. C is linear in Y1, so a straight line in
//    X1/Y1/Z is a straight line in X/C/Z: only the path feed needs r (C-axis manual 1.2's
//    effective distance).
//  - G30: off.
// A straight line of G31 is a curve in machine space. Its geometry along the arc length s from
// the foot of the perpendicular from the centre (distance d): r(s) = sqrt(d^2 + s^2),
// theta(s) = atan2(s, d). Derivatives used for the limits and the chord bound:
//   r'  = s / r          |r'|  <= 1
//   r'' = d^2 / r^3      <= d^2 / r_min^3
//   th' = d / r^2        <= d / r_min^2               (rad per mm)
//   th''= -2 d s / r^4   |th''| <= 3 sqrt(3) / (8 d^2) (at |s| = d / sqrt(3))
// A G02/G03 arc of G31 (centre c, radius R, D = |c| the centre's distance from the spindle
// axis, T the unit tangent, N the unit normal towards c, P the point, r = |P|):
//   r'  = P.T / r                               |r'|  <= 1
//   r'' = (1 - r'^2 + P.N / R) / r = -(r'^2 + c.u / R) / r   (u = (P - c) / R)
//                                               |r''| <= (1 + D / R) / r_min
//   th' = (P x T) / r^2                         |th'| <= 1 / r_min     (|P x T| <= r)
//   th''= (P x N) / (R r^2) - 2 (P x T)(P.T) / r^4
//                                               |th''| <= 1 / (R r_min) + 1 / r_min^2
//     (|(P x T)(P.T)| <= r^2 / 2). They bound the arc's path feed as the line's bound it.
// C along an arc: its polar angle unwound, th(end) - th(start) = the chord's SweepDeg plus
// 360 deg times the winding of arc-and-chord around the centre (+1 counter-clockwise, -1
// clockwise, if the centre lies between the arc and its chord); pieces of at most 90 deg of
// arc keep it simple (a piece's chord through the centre is split again).
// No include of the channel: the interpreter converts fictive words with these functions too.

#include <string>

namespace vmt::control::nc {

/// A point of the fictive Cartesian plane, mm.
struct FictivePoint {
  double x1 = 0, y1 = 0;
};

/// G31: the machine axes' (program coordinate) values of a face point: X radius >= 0, C in
/// degrees in (-180, 180]; C is 0 at the centre.
void FaceToMachine(FictivePoint p, double& x, double& c_deg);
/// G31: the face point of X (radius, may be negative) and C (deg).
FictivePoint MachineToFace(double x, double c_deg);
/// Signed angle from a to b about the centre, degrees in (-180, 180]; 0 if either is at the
/// centre. Along a straight line that misses the centre it is continuous: C(u) = C(0) + sweep.
double SweepDeg(FictivePoint a, FictivePoint b);
/// C (deg) nearest to `near_deg` that points at `p` (C of the centre: near_deg).
double FaceC(FictivePoint p, double near_deg);

/// G32: C (deg) of the arc length y1 on radius r, and back.
double CylinderC(double y1, double radius);
double CylinderY1(double c_deg, double radius);

/// mm: a G31 line that passes the centre closer than this is refused (C is undefined there:
/// it would turn half a revolution in no time).
inline constexpr double kFaceCentreClearance = 1e-3;

/// The geometry of a G31 line from a to b (or of an arc: FaceArcBoundsOf) that the limits and
/// PathGuard need.
struct FaceLine {
  double length = 0;         ///< mm
  double d = 0;              ///< distance of the line (extended) from the centre
  double r_min = 0, r_max = 0;  ///< nearest and furthest radius on the segment
  double theta_s_max = 0;    ///< max |dC/ds|, rad/mm
  double theta_ss_max = 0;   ///< max |d2C/ds2|, rad/mm^2
  double r_ss_max = 0;       ///< max |d2X/ds2|, 1/mm
  bool through_centre = false;  ///< r_min < kFaceCentreClearance with C not constant
};
FaceLine FaceLineOf(FictivePoint a, FictivePoint b);

/// A G02/G03 arc of G31 in the face: P(u) = centre + radius (cos, sin)(start_angle + sweep u).
struct FaceArc {
  FictivePoint centre;
  double radius = 0;
  double start_angle = 0;  ///< rad
  double sweep = 0;        ///< rad, < 0 clockwise (G02); +-2 pi a full circle
  FictivePoint At(double u) const;
  /// dP/du.
  FictivePoint Tangent(double u) const;
};

/// mm: an arc's radius at its start and at its end may differ this much (as in G17..G19).
inline constexpr double kFaceArcTolerance = 0.01;

/// The G31 arc from `from` to `to`, clockwise (G02) or not (G03), about from + (i, j) when
/// `has_centre`, else of radius `r` (r < 0: the arc over 180 deg). End point = start: a full
/// circle. Empty `error` on success, else why not (the caller places the error).
FaceArc FaceArcOf(FictivePoint from, FictivePoint to, bool clockwise, bool has_centre, double i,
                  double j, double r, std::string& error);
/// C's change (deg) along the arc from u = 0 to `u`: the polar angle unwound (a full circle
/// around the centre: +-360). Valid for an arc that misses the centre.
double FaceArcSweepDeg(const FaceArc& arc, double u = 1);
/// The limits' and PathGuard's geometry of the arc, as FaceLineOf gives a line's (d unused).
FaceLine FaceArcBoundsOf(const FaceArc& arc);

/// Chord step (mm of fictive path) so that machine-space chords, linear in X and C between
/// points of the line, stay within `tolerance_mm` of it in the face plane. Bound: linear
/// interpolation of f over a step h errs by at most max|f''| h^2 / 8 (f = r and f = theta);
/// a radius error dr and angle error dtheta at radius <= r_max displace the point by at most
/// dr + r_max dtheta. So h = sqrt(8 tol / (r_ss_max + r_max theta_ss_max)).
double FaceChordStep(const FaceLine& line, double tolerance_mm);

}  // namespace vmt::control::nc
