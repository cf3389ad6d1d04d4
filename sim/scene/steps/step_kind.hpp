#pragma once
// A kind of timeline step (docs/scene-format.md, `timeline:`): the YAML key that names it, how
// it is read and how it plays. Each kind lives in its own file of this folder, reading and
// playing side by side; ReadStep (scene_steps.hpp) and the timeline player look a kind up here.

#include <sstream>

#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim {

class YamlNode;

/// What a step is read from: the machine, the scene's NC, the step's node; `plc`: the scene has
/// a PLC program, so the timeline may only press keys.
struct StepSource {
  const MachineModel& m;
  const NcSetup& nc;
  const YamlNode& n;
  bool plc;
};

struct StepKind {
  const char* key;  ///< the step's YAML key
  /// Fills `s` from the key's node; `text` holds "timeline[i]: " and gets the step's wording.
  void (*read)(const StepSource& src, TimelineStep& s, std::ostringstream& text);
  /// Plays the step in one tick: true once it is done (the next step may begin in this tick).
  bool (*play)(const TimelineStep& s, const StepTick& tick, TimelinePlay& play);
};

/// The kind whose key the step node has, or null.
const StepKind* FindStepKind(const YamlNode& n);
/// The kind that read a step of `kind` and plays it.
const StepKind& StepKindOf(TimelineStep::Kind kind);

/// `parameter_set:` of a drive step (0..7, as SERCOS numbers them). A set the drive lacks is
/// not refused here: the drive reports it (kParameterSetError), which a scene may want to show.
int ReadDriveParameterSet(const YamlNode& step, std::ostringstream& text);

// The kinds, one file each.
extern const StepKind kMoveStep, kSpeedStep, kOrientStep, kOffStep, kOutputStep, kWaitStep,
    kWaitUntilStep, kNcStep, kJogStep, kHandwheelStep, kSignalStep, kFaultStep;

}  // namespace vmt::sim
