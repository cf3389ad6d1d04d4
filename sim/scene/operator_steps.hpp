#pragma once
// The operator station's inputs as a run records them (operator.yaml) and `vmt run --operator`
// reads them back: each a key or signal value taken at the start of a drive tick.
#include <cstdint>
#include <string>
#include <vector>

namespace vmt::sim {

/// One input of the operator station (vmt serve --http): a machine key of the model's io (dir:
/// key) or a signal the PLC writes, set to `value` at the start of drive tick `tick` (the first
/// tick of a PLC cycle), as the timeline's `press:` and `signal:` set them.
struct OperatorStep {
  int64_t tick = 0;
  std::string signal;     ///< a key or signal set to `value`; empty for a handwheel's turn
  double value = 0;       ///< the signal's value, or the handwheel's counts
  std::string handwheel;  ///< the axis whose handwheel turned `value` counts (X, Z, X1, ...)
};

/// Reads `operator: [{tick, signal, value} | {tick, handwheel, counts}, ...]` of an
/// operator.yaml; ticks must not go back.
/// Throws ModelError naming the file and YAML path of a bad entry. Whether each signal may be
/// set is checked when the run takes it.
std::vector<OperatorStep> ReadOperatorSteps(const std::string& file);

}  // namespace vmt::sim
