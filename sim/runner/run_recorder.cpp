#include "sim/runner/run_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "common/json_text.hpp"

namespace vmt::sim {

void RunRecorder::Open(const std::string& out_dir) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) throw common::WriteError(out_dir, error.value());
  // summary.json is written when the run is over: one from an earlier run must not say so.
  std::filesystem::remove(out_dir + "/summary.json", error);
  trace_file_ = std::make_unique<common::OutputFile>(out_dir + "/trace.csv");
  events_file_ = std::make_unique<common::OutputFile>(out_dir + "/events.jsonl",
                                                      common::OutputFile::Mode::kStream);
  writing_ = true;
}

void RunRecorder::Event(nlohmann::ordered_json event) {
  event["t"] = std::round(event["t"].get<double>() * 1e6) / 1e6;
  // Line by line, so that a PLC engineer can follow events.jsonl while the run goes on (tail -f).
  if (events_file_) {
    events_file_->Write(event.dump(-1, ' ', false, common::kReplaceBadUtf8) + '\n');
    Checked(events_file_, false);
  }
  for (const Observer& o : observers_) o.observe(event);
}

void RunRecorder::Signal(double t, const std::string& name, double value) {
  const bool observed = std::any_of(observers_.begin(), observers_.end(),
                                    [](const Observer& o) { return o.signals; });
  if (!events_file_ && !observed) return;
  t = std::round(t * 1e6) / 1e6;
  if (events_file_) {
    // The line Event writes, without building the object: its members' text in its order.
    using Json = nlohmann::ordered_json;
    events_file_->Write("{\"t\":" + Json(t).dump() + ",\"event\":\"signal\",\"name\":" +
                        Json(name).dump(-1, ' ', false, common::kReplaceBadUtf8) +
                        ",\"value\":" + Json(value).dump() + "}\n");
    Checked(events_file_, false);
  }
  if (!observed) return;
  const nlohmann::ordered_json event = {
      {"t", t}, {"event", "signal"}, {"name", name}, {"value", value}};
  for (const Observer& o : observers_)
    if (o.signals) o.observe(event);
}

void RunRecorder::Checked(std::unique_ptr<common::OutputFile>& file, bool close) {
  if (!file) return;
  try {
    close ? file->Commit() : file->Flush();
    if (close) file.reset();
  } catch (const common::WriteError& e) {
    AddWriteError(e.what());
    file.reset();  // the run goes on without it
  }
}

void RunRecorder::AddWriteError(const std::string& error) { write_errors_.push_back(error); }

void RunRecorder::Flush() {
  Checked(trace_file_, false);
  Checked(events_file_, false);
}

void RunRecorder::Close() {
  Checked(trace_file_, true);
  Checked(events_file_, true);
}

}  // namespace vmt::sim
