#pragma once
// The measuring instructions SETTING, SAVE, MOVE, PROBE, COMPARE, CORRECTION and RESTORE
// (mtc200-fast-measurement.md 2, 4, 6) as the real control treats them: each one "generates the
// NC blocks" that do its work. Here an instruction, with its arguments as the program wrote them,
// becomes a plan: a list of plain steps (events, waits, rapid moves, the measuring move, page
// writes) that the channel runs one after the other. The measured value comes back from the
// channel (the drive's latch) and is entered by FinishProbe.
//
// Coordinates in this file: workpiece coordinates of the centre of the active measuring sphere,
// mm, radius values (a G16 diameter is halved on the way in), per SETTING axis 1..3. The channel
// adds the zero offset and the stylus edge's tool length (SETTING E = 48) to get axis positions.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "control/measure/measuring_messages.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::measure {

/// A call with its arguments as the program wrote them (nc::InstructionCall).
using InstructionArg = nc::InstructionArg;
using InstructionCall = nc::InstructionCall;

/// True for the seven names above (the interpreter's nc::IsMeasuringCall).
inline bool IsMeasuringInstruction(const std::string& name) {
  return nc::IsMeasuringCall(nc::InstructionOf(name));
}

/// What SETTING (A..G) established; kept by the channel from SETTING to the end of the program
/// (Control-Reset clears it).
struct MeasuringSetting {
  std::array<char, 3> axis{};  ///< 'X', 'Y', 'Z' or 0 (empty place), SETTING A..C
  nc::Plane plane = nc::Plane::kZX;  ///< D: G17, G18, G19
  nc::ToolLength tool_length = nc::ToolLength::kAdd;  ///< E: G47, G48
  bool diameter = false;       ///< F: G16
  int stylus = 1;              ///< G: 1..4, TASTWERKZEUGPAGE LV1
  /// What the last SAVE(A, B, C) kept: variables, axis positions, F (RESTORE writes back only
  /// these, 2.1 RESTORE); none before the first SAVE. A later SETTING keeps it.
  std::optional<std::array<bool, 3>> saved;
};

/// One point of the reverse vectors: the sphere centre and the sphere it is the centre of. The
/// instructions of a record may name different spheres (figure 4-9: blocks 54, 55 change from
/// sphere 1 to 4); the axes stood at the centre plus that sphere's offsets, so the way back must
/// use the same sphere to reach the same axis positions.
struct ReversePoint {
  std::array<double, 3> centre{};
  int sphere = 1;
};

/// The reverse vectors of 4.4: the points the stylus passed through, per reverse variant, so that
/// the reverse program can first take the stylus back the way it came.
struct ReverseVectors {
  /// Single point (variant 0): the moves of the MOVE / PROBE in progress or last completed;
  /// replaced by each instruction of variant 0.
  std::vector<ReversePoint> single_point;
  /// Linear path sequences 1..10: the points since the sequence's first instruction. A sequence
  /// ends (is cleared) when an instruction of another variant follows it.
  std::array<std::vector<ReversePoint>, 10> sequence;
  int active = 0;  ///< the variant of the last MOVE / PROBE (0 = single point)

  /// The record of the active variant.
  std::vector<ReversePoint>& Active();
  const std::vector<ReversePoint>& Active() const;
  /// The points to travel, in order, before the reverse program `.HOME` runs: the recorded points
  /// of the active variant back to its first one. Empty if nothing is recorded.
  std::vector<ReversePoint> Reversal() const;
};

/// The state an instruction starts from, as the channel knows it.
struct MeasuringContext {
  int process = 0;                      ///< LV1 of the PROCESS pages
  std::optional<MeasuringSetting> setting;  ///< none before the first SETTING
  bool turning = true;       ///< a lathe: G16 allowed in SETTING (4.1)
  bool tool_list = true;     ///< a tool list exists: G48 may be set (4.1)
  nc::Compensation compensation = nc::Compensation::kOff;  ///< 4.1: MOVE and PROBE need G40
  /// The sphere centre now, workpiece coordinates per SETTING axis (radius values).
  std::array<double, 3> position{};
  /// The modal G groups 1, 2, 3, 5, 6, 7, 13 now, as G(n) reads them (ZWISCHENSPEICHERPAGE 3..9).
  std::array<int16_t, 7> g_groups{};
  std::array<double, 13> variables{};  ///< @100..@112 now (SAVE)
  double feed = 0;                     ///< F now (SAVE)
};

/// One step of a plan.
struct MeasuringStep {
  enum class Kind : uint8_t {
    kEvent,       ///< set (value) or reset event `event` (6.2: 29, 30)
    kWaitEvent,   ///< wait until event `event` is `value` (6.2: E29 = 0 from the PLC)
    kAux,         ///< Q function `q` to the PLC, wait for its acknowledgement (6.1: Q9992)
    kRapid,       ///< G00 (G94) of the `axes` to `target`
    kMeasure,     ///< G01 G94 at `feed` (mm/min) to `target`, the measuring path: it ends at the
                  ///< first contact (the drive's latch), else at `target`
  };
  Kind kind = Kind::kEvent;
  int event = 0;
  bool value = false;
  int q = 0;
  std::array<double, 3> target{};
  uint8_t axes = 0;  ///< bit n: SETTING axis n+1 moves
  double feed = 0;
  int sphere = 1;  ///< the measuring sphere (stylus tool edge) the move is for
};

/// What one instruction does. The channel runs `steps`, then (for PROBE) calls FinishProbe with
/// the measured value, then applies what the plan says about the setting and variables.
struct MeasuringPlan {
  std::string error;  ///< "" or the program error (4.1, parameter ranges, placement)
  std::vector<MeasuringStep> steps;
  /// SETTING: the new setting; the channel also makes its G codes (plane, G47/G48, G15/G16)
  /// modal in the program, as the generated blocks of the real control do. SAVE: the setting
  /// with what it saved (MeasuringSetting::saved); the channel keeps whichever plan sets it.
  std::optional<MeasuringSetting> setting;
  /// RESTORE: what SAVE kept and is written back (variables @100..@112, F); axis positions are
  /// not moved (2.1 RESTORE).
  std::optional<std::array<double, 13>> restore_variables;
  std::optional<double> restore_feed;
  /// PROBE: the measuring move's axis (0..2 = SETTING axis 1..3) and direction (+1 / -1), the
  /// command value of the surface (radius value along the axis), for FinishProbe. A calibration
  /// PROBE hidden by ZWISCHENSPEICHERPAGE element 1 (3.1) plans no steps and leaves
  /// measuring_axis -1: FinishProbe then does nothing.
  int measuring_axis = -1;
  int direction = 0;
  double command = 0;
  /// MOVE / PROBE: the stylus' points recorded for the reverse program (4.4).
  int reverse_variant = 0;
  /// CORRECTION: the message its dimensional accuracy asks for (OVERSIZE, UNDERSIZE, CHECK TOOL,
  /// ILLEGALLY HIGH DIMENSIONAL DEVIATION); nullptr for accuracy 0 and the other instructions.
  const MeasuringMessage* message = nullptr;
  /// "" or a warning for the operator that does not stop the program (a measuring PROBE at a
  /// feed other than its direction's calibration feed).
  std::string warning;
};

/// Plans one instruction. `pages` may be written at once by the instructions that do no moving
/// (SETTING: BASISMESSPAGE 6..10; SAVE: ZWISCHENSPEICHERPAGE; COMPARE; CORRECTION: ERGEBNISPAGE),
/// `reverse` by MOVE / PROBE.
MeasuringPlan PlanInstruction(const InstructionCall& call, const MeasuringContext& context,
                              MeasuringPages& pages, ReverseVectors& reverse);

/// After a PROBE's measuring move: `contact` is the sphere centre's position along the measuring
/// axis when the probe switched (radius value, workpiece coordinates), nullopt if it did not
/// switch on the whole measuring path. Calibration (B = 0) writes EICHWERTEPAGE, measurement
/// (B = 1) POINTPAGE. Returns the message to issue (kTestPointNotFound) or nullptr.
const MeasuringMessage* FinishProbe(const InstructionCall& call, const MeasuringPlan& plan,
                                    const MeasuringContext& context, MeasuringPages& pages,
                                    std::optional<double> contact);

}  // namespace vmt::control::measure
