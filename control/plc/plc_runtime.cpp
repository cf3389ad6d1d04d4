#include "control/plc/plc_runtime.hpp"

#include "common/demand.hpp"

namespace vmt::control::plc {

bool PlcDrives(gateway::Direction direction) {
  using gateway::Direction;
  return direction == Direction::kPlcToNc || direction == Direction::kPlcToMachine ||
         direction == Direction::kShared;
}

void DropPlcOutputs(gateway::SignalImage& image) {
  using gateway::Direction;
  const gateway::SignalImage presets(image.table());
  for (int id = 0; id < image.size(); ++id) {
    const Direction d = image.table()[id].direction;
    if (d == Direction::kPlcToNc || d == Direction::kPlcToMachine) image.CopyValue(id, presets);
  }
}

void PlcScan::Writable(int id) const {
  // A PLC program that writes an NC status or a machine input is wrong as compiled code is
  // wrong: stop with its name rather than let the write vanish at the end of the scan.
  const bool writable = id >= 0 && id < static_cast<int>(writable_.size()) && writable_[id];
  VMT_DEMAND(writable, "plc: the program writes %s (id %d), which the PLC does not drive",
             id >= 0 && id < latched_.size() ? latched_.table()[id].name.c_str() : "?", id);
}

PlcRuntime::PlcRuntime(gateway::SignalImage& image, PlcProgram program, PlcTime period)
    : image_(image), latched_(image.table()), program_(std::move(program)), period_(period) {
  writable_.resize(image.size());
  for (int id = 0; id < image.size(); ++id) {
    writable_[id] = PlcDrives(image.table()[id].direction);
    if (writable_[id]) outputs_.push_back(id);
  }
}

void PlcRuntime::Scan() {
  if (stopped_) return;
  latched_.CopyValuesFrom(image_);
  PlcScan scan(latched_, writable_, now_, cycles_, axd_wr_ ? &axd_wr_ : nullptr);
  program_(scan);
  for (int id : outputs_) image_.CopyValue(id, latched_);
  now_ += period_;
  ++cycles_;
}

void PlcRuntime::Stop() {
  stopped_ = true;
  DropPlcOutputs(image_);
}

}  // namespace vmt::control::plc
