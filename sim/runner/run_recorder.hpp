#pragma once
// What a run leaves behind and who watches it: the trace (its rows feed the digest that pins a
// scene's behaviour, and trace.csv), the events (events.jsonl) and the observers an event is
// handed to as it happens - the event snapshots, a caller's callback, a live view.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "common/output_file.hpp"

namespace vmt::sim {

/// The trace's digest: same scene, same bytes, same digest.
class Fnv1a64 {
 public:
  void Add(std::string_view s) {
    // In a local: the bytes are chars, which may alias the member, so a loop on the member
    // stores it back after every byte.
    uint64_t hash = hash_;
    for (unsigned char c : s) hash = (hash ^ c) * 0x100000001b3ull;
    hash_ = hash;
  }
  std::string Hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash_));
    return buf;
  }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

class RunRecorder {
 public:
  using EventObserver = std::function<void(const nlohmann::ordered_json&)>;

  /// Observers see every event in the order they were added, after it is written; with
  /// `signals` false, all but the signal events (thousands in a run, and built for nobody else).
  void AddObserver(EventObserver observer, bool signals = true) {
    observers_.push_back({std::move(observer), signals});
  }

  /// Writes trace.csv and events.jsonl into `out_dir` (created) from here on; without it the
  /// run only digests its trace and hands events to the observers. Throws common::WriteError
  /// if it cannot create them.
  void Open(const std::string& out_dir);
  bool writing() const { return writing_; }

  void Trace(std::string_view row) {
    digest_.Add(row);
    if (trace_file_) trace_file_->Write(row);  // checked at Flush and Close, not per row
  }
  /// Rounds the event's time to the tick grid (3.4995, not 3.4995000000000003), writes it (a
  /// whole line to the file at once, as it happens) and hands it to the observers.
  void Event(nlohmann::ordered_json event);
  /// A signal's new value (an event "signal"), as Event would write and hand it on; built only
  /// when it is written or an observer takes signal events.
  void Signal(double t, const std::string& name, double value);

  std::string DigestHex() const { return digest_.Hex(); }
  /// What is written so far handed to the system (the run goes on). A file that failed is
  /// dropped (trace.csv: its temporary removed; events.jsonl: its whole lines kept) and the
  /// run goes on without it; the failure is in write_errors().
  void Flush();
  /// The run is over: trace.csv renamed to its name (complete), events.jsonl closed.
  void Close();
  /// A file the run could not write ("cannot write FILE: REASON"), or any other output of the
  /// run (summary.json, a picture): each is reported once, in order.
  void AddWriteError(const std::string& error);
  const std::vector<std::string>& write_errors() const { return write_errors_; }

  /// The digest so far and the write errors: what a run that writes no files has recorded,
  /// kept to go back to (SceneRun::Save).
  struct Saved {
    Fnv1a64 digest;
    std::vector<std::string> write_errors;
  };
  Saved Save() const { return {digest_, write_errors_}; }
  void Restore(const Saved& saved) {
    digest_ = saved.digest;
    write_errors_ = saved.write_errors;
  }

 private:
  void Checked(std::unique_ptr<common::OutputFile>& file, bool close);

  Fnv1a64 digest_;
  bool writing_ = false;
  // trace.csv is whole or missing (a temporary renamed at Close); events.jsonl is streamed, a
  // whole line at a time, so that it can be followed as the run goes on.
  std::unique_ptr<common::OutputFile> trace_file_, events_file_;
  std::vector<std::string> write_errors_;
  struct Observer {
    EventObserver observe;
    bool signals;
  };
  std::vector<Observer> observers_;
};

}  // namespace vmt::sim
