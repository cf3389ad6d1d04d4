#pragma once
// What a run leaves behind and who watches it: the trace (its rows feed the digest that pins a
// scene's behaviour, and trace.csv), the events (events.jsonl) and the observers an event is
// handed to as it happens - the event snapshots, a caller's callback, a live view.

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vmt::sim {

/// The trace's digest: same scene, same bytes, same digest.
class Fnv1a64 {
 public:
  void Add(const std::string& s) {
    for (unsigned char c : s) hash_ = (hash_ ^ c) * 0x100000001b3ull;
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

  /// Observers see every event in the order they were added, after it is written.
  void AddObserver(EventObserver observer) { observers_.push_back(std::move(observer)); }

  /// Writes trace.csv and events.jsonl into `out_dir` (created) from here on; without it the
  /// run only digests its trace and hands events to the observers. Throws if it cannot write.
  void Open(const std::string& out_dir);
  bool writing() const { return writing_; }

  void Trace(const std::string& row) {
    digest_.Add(row);
    if (writing_) trace_file_ << row;
  }
  /// Rounds the event's time to the tick grid (3.4995, not 3.4995000000000003), writes it (a
  /// whole line to the file at once, as it happens) and hands it to the observers.
  void Event(nlohmann::ordered_json event);

  std::string DigestHex() const { return digest_.Hex(); }
  /// The files complete on disk, whether or not the run goes on.
  void Flush();

 private:
  Fnv1a64 digest_;
  bool writing_ = false;
  std::ofstream trace_file_, events_file_;
  std::vector<EventObserver> observers_;
};

}  // namespace vmt::sim
