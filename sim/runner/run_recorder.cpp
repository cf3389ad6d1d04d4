#include "sim/runner/run_recorder.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace vmt::sim {

void RunRecorder::Open(const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  trace_file_.open(out_dir + "/trace.csv", std::ios::binary);
  events_file_.open(out_dir + "/events.jsonl", std::ios::binary);
  if (!trace_file_ || !events_file_)
    throw std::runtime_error("cannot write to output folder " + out_dir);
  writing_ = true;
}

void RunRecorder::Event(nlohmann::ordered_json event) {
  event["t"] = std::round(event["t"].get<double>() * 1e6) / 1e6;
  // Line by line, so that a PLC engineer can follow events.jsonl while the run goes on (tail -f).
  if (writing_) events_file_ << event.dump() << '\n' << std::flush;
  for (const EventObserver& observe : observers_) observe(event);
}

void RunRecorder::Flush() {
  trace_file_.flush();
  events_file_.flush();
}

}  // namespace vmt::sim
