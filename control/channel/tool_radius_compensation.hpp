#pragma once
// Tool nose radius compensation (G40/G41/G42) in the G18 plane of a lathe, as pure geometry: the
// channel pushes the programmed contour one element at a time and pops the path of the
// theoretical tool tip (the point the tool length refers to), one block of look-ahead.
//
// Frame: points are (z, x) with x a radius (the caller converts diameter programming). The frame
// is treated like a normal (horizontal, vertical) one: counter-clockwise (G03) turns from +Z
// towards +X, G02 the other way. "Left" of a direction d is d rotated by +90 degrees.
//
// The nose centre runs at the nose radius r from the programmed contour, on the left (G41) or
// right (G42) looking along the motion; the tip point the channel moves is the nose centre plus
// TipFromCentre(edge position, r).
//
// Rules (as on common lathe controls: perpendicular start-up and cancel, trimmed inner corners,
// arcs around outer corners):
// - Start-up: the first moving block with G41/G42 after G40 must be a line. It runs from its
//   uncompensated start point to the end point offset perpendicular to the FOLLOWING element at
//   that element's start (perpendicular to itself when nothing follows before a Flush or a
//   cancel). No corner is inserted between the start-up block and the next element.
// - Cancel: the first moving block with G40 after G41/G42 must be a line. The element before it
//   ends offset perpendicular at its own end point; the cancel block runs from there to its own
//   uncompensated end point.
// - Side change (G41 <-> G42 on a moving block): cancel and start-up in one block, which must be
//   a line: the previous element ends perpendicular at its end, the side-change block runs from
//   there to its end point offset on the new side perpendicular to the following element. A new
//   nose radius or edge position may come with it (it is a start-up).
// - Corners between two compensated elements (line-line, line-arc, arc-arc):
//   tangent (turn within 1e-9 rad, or the two offset points within 1e-9 mm): nothing inserted;
//   inner (the tool on the inside of the turn): both offset elements are trimmed to the
//   intersection of their offset curves nearest to the programmed corner;
//   outer (and a reversal by 180 degrees): a transition arc of radius r centred on the
//   programmed corner point joins the two perpendicular offset points (G02 under G41, G03 under
//   G42).
// - Blocks that move nothing in the plane (zero-length lines) keep their place in the output as
//   zero-length lines at the tip point reached there; the corner is computed between the moving
//   elements around them, and they never start or cancel the compensation (a G41/G42/G40 on such
//   a block takes effect on the next moving block).
// - Adjacent offset elements that cross each other away from their joint (the contour comes
//   back within r, e.g. an arc curling back over the element before it) are a contour
//   violation, as are elements too short for the trimming at inner corners. Only adjacent
//   elements are checked (one element of look-ahead).
// - Flush ends the held-back element perpendicular at its end point because the next element
//   is not known: at what turns out to be an inner corner the nose then overlaps the next
//   element by up to r, as on every control that cannot look ahead. So a block that only stops
//   the machine (M00, M01, a dwell) should be pushed as a zero-length element, and the
//   channel should read on to the next moving block before running the held-back one; Flush
//   is for the program end and for blocks whose successors cannot be prepared yet (a
//   preprocessing stop). If the compensation is still active after a Flush, the next element
//   is joined to the last one as a corner: outer -> transition arc, inner -> the tool first
//   runs back along the last offset element to the intersection (an inserted element on that
//   offset curve), then on.
// - Errors stop the compensation for good (until Reset): elements finalised before the error
//   stay available from Pop; the held-back element is dropped and further pushes are ignored.

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace vmt::control::channel {

/// A point or vector in the G18 plane: z first, x second (x as a radius), mm.
struct Vec2 {
  double z = 0;
  double x = 0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.z + b.z, a.x + b.x}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.z - b.z, a.x - b.x}; }
inline Vec2 operator-(Vec2 a) { return {-a.z, -a.x}; }
inline Vec2 operator*(double k, Vec2 a) { return {k * a.z, k * a.x}; }
inline double Dot(Vec2 a, Vec2 b) { return a.z * b.z + a.x * b.x; }
/// z-component of the 3D cross product: > 0 when b lies counter-clockwise (left) of a.
inline double Cross(Vec2 a, Vec2 b) { return a.z * b.x - a.x * b.z; }
double Norm(Vec2 a);

/// Direction from the nose centre to the theoretical tool tip for a cutting edge position (the
/// 1..9 numbering of the imaginary tool nose / cutting edge position), stated in the (Z, X)
/// frame above, +X up:
///
///   edge  tip - centre      edge  tip - centre
///    1    (+r, +r)           5    ( 0, +r)
///    2    (-r, +r)           6    (-r,  0)
///    3    (-r, -r)           7    ( 0, -r)
///    4    (+r, -r)           8    (+r,  0)
///    9, 0 ( 0,  0): the tip is the nose centre
///
/// Example: an outside turning tool that approaches from +X and cuts towards -Z (towards the
/// chuck) has its theoretical tip at (-r, -r) from the nose centre: edge position 3. Values
/// outside 0..9 give (0, 0) (ToolRadiusCompensation rejects them).
Vec2 TipFromCentre(int edge_position, double r);

enum class ElementKind { kLine, kArcCw, kArcCcw };    ///< G01 (or G00), G02, G03
enum class CompensationSide { kOff, kLeft, kRight };  ///< G40, G41, G42

/// One programmed contour element (input) or one element of the tip path (output).
struct ContourElement {
  ElementKind kind = ElementKind::kLine;
  Vec2 start;
  Vec2 end;
  Vec2 centre;  ///< arcs only; start == end (within 1e-9 mm) is a full circle
  /// Compensation modal state of this block (input); copied to the output.
  CompensationSide side = CompensationSide::kOff;
  double nose_radius_mm = 0;  ///< r of the active tool correction, >= 0 (ignored under G40)
  int edge_position = 0;      ///< cutting edge position 0..9 (ignored under G40)
  int64_t tag = 0;            ///< the caller's block id, passed through
  bool rapid = false;         ///< G00; passed through
  /// Output only: a transition element the compensation inserted (corner arc, or the run back
  /// along the last element after a Flush). It carries tag, rapid, side, radius and edge
  /// position of the block it PRECEDES (the block after the corner).
  bool inserted = false;
};

/// Signed sweep of an arc, rad: > 0 counter-clockwise (G03), < 0 clockwise (G02); a full circle
/// (start == end within 1e-9 mm) is +-2 pi. 0 for lines. Same convention as the channel's arc
/// interpolation.
double ArcSweep(const ContourElement& arc);

struct CompensationError {
  int64_t tag = 0;      ///< block the error belongs to
  std::string message;  ///< without position; the caller prefixes file:line:column
};

/// Internal state of ToolRadiusCompensation: the nose-centre path of one programmed element.
struct OffsetElement {
  ContourElement block;  ///< as programmed; start joined to the previous end, arc end on the arc
  double sweep = 0;      ///< arcs: programmed sweep, rad (ArcSweep)
  double offset_radius = 0;  ///< arcs: radius of the nose-centre arc, mm
  double s = 0;              ///< +1 G41 (left), -1 G42 (right)
  Vec2 tip;                  ///< TipFromCentre(edge position, r)
  Vec2 q0, q1;               ///< nose centre at the start and at the end (after trimming)
  bool start_up = false;     ///< start-up (or side-change) line
  Vec2 start_up_from;        ///< start-up: where the tip starts (uncompensated point)
};

/// Streaming tool nose radius compensation with one element of look-ahead.
///
/// Usage: Push each programmed element in order; Pop whatever is final; when Pop returns false
/// and pending() is true, the next element is needed (or a Flush) before the held-back one can
/// be moved. Call Flush at program end or where the following blocks cannot be prepared: the
/// held-back element is finalised as followed by nothing (see the file comment on stops).
/// Consecutive compensated elements must join within 0.01 mm (the channel's arc end point
/// tolerance); they are joined exactly.
///
/// Output elements are in tip coordinates and keep the tag of their block. Elements under G40
/// (other than the cancel block) come out unchanged. Output arcs always have consistent radii;
/// a compensated arc whose remaining piece is shorter than 1e-9 mm, or whose nose-centre radius
/// is 0 (arc radius == nose radius on the inner side), comes out as a (zero-length) line.
///
/// Errors (error(); message texts are part of the contract and tested):
/// - "G41/G42 start-up on an arc: the block that starts tool nose radius compensation must be
///   a straight line (G00/G01)"
/// - "G40 cancel on an arc: the block that cancels tool nose radius compensation must be a
///   straight line (G00/G01)"
/// - "G41/G42 side change on an arc: the block that changes the compensation side must be a
///   straight line (G00/G01)"
/// - "tool nose radius changed while G41/G42 is active (r <old> -> <new> mm): cancel with G40
///   first"
/// - "cutting edge position changed while G41/G42 is active (<old> -> <new>): cancel with G40
///   first"
/// - "arc radius <R> mm smaller than the tool nose radius <r> mm on the inner side of the arc"
/// - "contour violation (gouge): the block is too short for the tool nose radius <r> mm at an
///   inner corner, the compensated path would run backwards" (tag: that block)
/// - "contour violation (gouge): the offset contour has no intersection at the inner corner,
///   the tool nose radius <r> mm does not fit" (tag: the block after the corner)
/// - "contour violation (gouge): the compensated path of the block crosses that of the block
///   before, the contour comes back within the tool nose radius <r> mm" (tag: the later block)
/// - "contour not continuous under G41/G42: the block starts <d> mm away from the previous end
///   point"
/// - "invalid cutting edge position <n> (0..9)", "negative tool nose radius <r> mm",
///   "arc centre on the arc start point", "arc centre on the arc end point"
class ToolRadiusCompensation {
 public:
  /// Adds the next programmed element. Ignored after an error.
  void Push(const ContourElement& element);
  /// Takes the next final element of the tip path; false when none is final yet.
  bool Pop(ContourElement& out);
  /// Finalises the held-back element as followed by nothing (its end offset perpendicular at
  /// its end point). The compensation stays active.
  void Flush();
  /// An element is held back waiting for its successor.
  bool pending() const { return pending_.has_value(); }
  /// Between start-up and cancel.
  bool active() const { return active_; }
  const std::optional<CompensationError>& error() const { return error_; }
  /// Back to G40 with nothing queued and no error.
  void Reset();

 private:
  void ZeroLength(const ContourElement& e);
  void StartUp(const ContourElement& e, bool side_change);
  void Cancel(const ContourElement& e);
  void Continue(const ContourElement& e);
  /// Joins `b` to `a`: the held-back element (a_emitted false) or, after a Flush, the last
  /// emitted one. Adjusts a.q1 and b.q0 and appends inserted elements to `inserted`.
  bool Corner(OffsetElement& a, OffsetElement& b, bool a_emitted,
              std::vector<ContourElement>& inserted);
  bool MakeOffset(const ContourElement& e, Vec2 start, OffsetElement& out);
  /// False (with an error) when a finalised element would run backwards (too short).
  bool RunsForward(const OffsetElement& a);
  /// False (with an error) when the offset of `b` crosses that of `a` away from their joint.
  bool NoLoop(const OffsetElement& a, const OffsetElement& b);
  /// Checks that a finalised element does not run backwards and queues its tip element.
  bool Emit(const OffsetElement& a);
  /// Emits the held-back element as it is (followed by nothing) and the zero-length blocks
  /// after it.
  bool FinishPending();
  /// Programmed end point of the last compensated element (held back or emitted).
  Vec2 ProgrammedEnd() const;
  /// Tip point at the end of the last emitted compensated element.
  Vec2 TipNow() const;
  /// False (with an error) when `start` is not the programmed end of the previous element.
  bool CheckContinuity(const ContourElement& e);
  void Fail(int64_t tag, std::string message);

  bool active_ = false;
  CompensationSide side_ = CompensationSide::kOff;
  double r_ = 0;
  int edge_ = 0;
  std::optional<OffsetElement> pending_;  ///< held back: its end depends on the next element
  std::vector<ContourElement> deferred_;  ///< zero-length blocks after pending_
  std::optional<OffsetElement> last_;     ///< last emitted compensated element
  std::deque<ContourElement> out_;
  std::optional<CompensationError> error_;
};

}  // namespace vmt::control::channel
