#pragma once
// The channel's error messages: a number the gateway shows the PLC (PxxS error number) and the
// operator's text. The MTC200 manuals do not list the NC's own message numbers (only the probe
// block's, mtc200-fast-measurement.md 7.2, which the probe block sends), so these are vmt's,
// grouped like a control's: 1xx program, 2xx geometry and feed, 3xx tools and offsets,
// 4xx operation, 5xx machine.

namespace vmt::control::channel {

inline constexpr int kMsgProgramError = 101;      ///< the NC program: syntax or run-time error
inline constexpr int kMsgNotAvailable = 102;      ///< a function the channel does not offer yet
inline constexpr int kMsgNoFeed = 201;            ///< G01/G02/G03 without F
inline constexpr int kMsgArcGeometry = 202;       ///< centre/radius do not fit the end point
inline constexpr int kMsgArcPlane = 203;          ///< the plane's axes are not in the channel
inline constexpr int kMsgSpindleStill = 204;      ///< G33/G63/G64 without M3/M4 and S
inline constexpr int kMsgLeadTooFast = 205;       ///< G33/G63/G64: lead x speed beyond a limit
/// G31/G32: a coordinate transformation cannot run (no rotary axis mode, a line through the
/// face's centre, a motion it does not offer).
inline constexpr int kMsgTransformation = 206;
inline constexpr int kMsgToolNotInList = 301;     ///< G48/G49 with a T/D the tool list lacks
inline constexpr int kMsgTranslationInArc = 302;  ///< offset or tool change in an arc block
inline constexpr int kMsgGouge = 303;  ///< tool nose radius compensation: contour violation
/// G92 of the rotary axis outside rotary axis mode (C-axis manual 2.3 Zero Point Shifts).
inline constexpr int kMsgOffsetInSpindleMode = 304;
inline constexpr int kMsgLeftContour = 401;  ///< continue after jogging off the contour
inline constexpr int kMsgNoHomeLabel = 402;  ///< reverse without a .HOME label
inline constexpr int kMsgMdiSyntax = 403;    ///< the MDI text does not parse
/// G77 while neither repositioning nor NC-block restart is active (REPOS manual 7.1).
inline constexpr int kMsgReposNotActive = 404;
inline constexpr int kMsgReposNoFeed = 405;  ///< G77 of a feed axis without F (4.2)
/// G77 S1=0 after rotary axis mode, G77 C0 after spindle mode (4.2).
inline constexpr int kMsgReposMode = 406;
/// Start of repositioning with the state not restored and no REPOS subroutine (4.1).
inline constexpr int kMsgReposNoSubroutine = 407;
/// The REPOS subroutine returned with the spindle not restored (4.1).
inline constexpr int kMsgReposNotRestored = 408;
/// Block search cannot run as parameterised: its CNC objects out of range, an entry point
/// beyond the program, G74/G100 where they cannot be simulated (twincat block search 4.1.2).
inline constexpr int kMsgBlockSearch = 409;
/// Block search with manual return: the axes stand further from the continue position than
/// mc_cmd_bs_deviation_max_w allows (4.2).
inline constexpr int kMsgBlockSearchDeviation = 410;
/// P-ERR-21399: the continue position lies in a region #BLOCKSEARCH LOCKED (block search 6).
/// The manual's own number.
inline constexpr int kMsgBlockSearchLocked = 21399;
/// Backward travel refused (block search 4.3): an offset after manual return, no path behind
/// the axes, repositioning in work. A message, not an error: the program stays held.
inline constexpr int kMsgBackward = 411;
inline constexpr int kMsgNotHomed = 501;        ///< a move of an axis that has no reference
inline constexpr int kMsgSoftwareLimit = 502;   ///< a target beyond the axis' travel
inline constexpr int kMsgDriveFault = 503;      ///< a drive of the channel is not ready
inline constexpr int kMsgFollowingError = 504;  ///< an axis lags beyond its following error limit
inline constexpr int kMsgPlcFault = 505;        ///< the PLC stopped (watchdog)
/// ROTMOD_Q / SPMOD_Q removed in the mode it acknowledges (C-axis manual 4.1: process error).
inline constexpr int kMsgChangeoverAck = 506;
/// PathGuard: the move would bring two parts of the machine into contact; stopped before it.
inline constexpr int kMsgCollision = 507;
/// AxxC.OTRVL: an axis' or the spindle's safety limit switch opened (C-axis manual 4.2).
inline constexpr int kMsgSafetyLimitSwitch = 508;
/// AxxC.MTAS: a motor's thermal protection switch opened (C-axis manual 4.2).
inline constexpr int kMsgThermalSwitch = 509;
/// A headstock changeover has waited for the PLC's acknowledgement too long (a notice: the
/// program waits on; HeadstockChangeover::Stalled says why).
inline constexpr int kMsgChangeoverStalled = 510;

/// Fast measurement: a measuring instruction cannot run (its parameters, its place, 4.1).
inline constexpr int kMsgMeasuringInstruction = 601;
/// Fast measurement, Q9998 (fault category 2): OVERSIZE / UNDERSIZE; the program holds and a
/// new start continues it.
inline constexpr int kMsgMeasuringContinuable = 602;
/// Fast measurement, Q9999 (fault category 1): TEST POINT NOT FOUND, ILLEGALLY HIGH DIMENSIONAL
/// DEVIATION, CHECK TOOL; only the reverse program (or Control-Reset) goes on.
inline constexpr int kMsgMeasuringReverseOnly = 603;

/// The operator text of a message number ("program error", ...).
inline const char* MessageText(int number) {
  switch (number) {
    case kMsgProgramError:
      return "program error";
    case kMsgNotAvailable:
      return "function not available";
    case kMsgNoFeed:
      return "no feed programmed";
    case kMsgArcGeometry:
      return "arc end point does not fit";
    case kMsgArcPlane:
      return "arc plane axis missing";
    case kMsgSpindleStill:
      return "spindle not turning for G33/G63/G64";
    case kMsgLeadTooFast:
      return "lead x spindle speed too fast for the axes";
    case kMsgToolNotInList:
      return "tool correction not in the tool list";
    case kMsgTranslationInArc:
      return "offset change in an arc block";
    case kMsgLeftContour:
      return "axes off the contour";
    case kMsgNoHomeLabel:
      return "no reverse program .HOME";
    case kMsgMdiSyntax:
      return "MDI block error";
    case kMsgBlockSearch:
      return "block search not possible";
    case kMsgBlockSearchDeviation:
      return "block search: axes too far from the continue position";
    case kMsgBlockSearchLocked:
      return "continue position locked for block search";
    case kMsgBackward:
      return "backward travel not possible";
    case kMsgReposNotActive:
      return "G77 without repositioning";
    case kMsgReposNoFeed:
      return "G77 without F";
    case kMsgReposMode:
      return "G77: spindle / rotary axis mode";
    case kMsgReposNoSubroutine:
      return "no REPOS subroutine";
    case kMsgReposNotRestored:
      return "state before interruption not restored";
    case kMsgNotHomed:
      return "axis not homed";
    case kMsgSoftwareLimit:
      return "software limit";
    case kMsgOffsetInSpindleMode:
      return "zero offset of the rotary axis in spindle mode";
    case kMsgGouge:
      return "contour violation (tool nose radius)";
    case kMsgDriveFault:
      return "drive not ready";
    case kMsgFollowingError:
      return "following error too large";
    case kMsgPlcFault:
      return "PLC not running";
    case kMsgChangeoverAck:
      return "spindle / rotary axis mode acknowledgement removed";
    case kMsgCollision:
      return "collision ahead";
    case kMsgSafetyLimitSwitch:
      return "safety limit switch";
    case kMsgThermalSwitch:
      return "thermal protection switch";
    case kMsgChangeoverStalled:
      return "spindle / rotary axis changeover not acknowledged";
    case kMsgTransformation:
      return "coordinate transformation error";
    case kMsgMeasuringInstruction:
      return "measuring instruction error";
    case kMsgMeasuringContinuable:
      return "measuring: dimension out of tolerance (Q9998)";
    case kMsgMeasuringReverseOnly:
      return "measuring: reverse program only (Q9999)";
    default:
      return "";
  }
}

}  // namespace vmt::control::channel
