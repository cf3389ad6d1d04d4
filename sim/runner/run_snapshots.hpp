#pragma once
// The pictures of a run: the timed ones (`at:`) and those of events (`on:`, each up to its
// limit), taken at the tick they fall due - the joint positions and the workpiece as turned
// then - and rendered at once, or after the run (a study's cases). Each picture written is
// announced as an event "snapshot".

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sim/backend/machine_backend.hpp"
#include "sim/collision/stock_cutter.hpp"
#include "sim/runner/run_recorder.hpp"
#include "sim/runner/scene_renderer.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// What the pictures of a tick show: the machine, and the stock as cut so far (null and 0: the
/// workpiece as the scene made it).
struct SnapshotSource {
  const MachineBackend& backend;
  const StockCutter* cutter = nullptr;
  int64_t stock_cuts = 0;  ///< ticks in which the turned stock changed
};

/// How a run takes its pictures (RunOptions' snapshots, snapshots_after_run and out_dir).
struct SnapshotSettings {
  bool take = true;        ///< false: no pictures at all
  bool after_run = false;  ///< rendered at the run's end, not as taken
  std::string out_dir;
};

class RunSnapshots {
 public:
  RunSnapshots(const Scene& scene, SnapshotSettings settings);

  /// An event was recorded: the pictures of the scene's `on:` snapshots for it are due at this
  /// tick's end (the recorder's observer).
  void NoteEvent(const nlohmann::ordered_json& event);
  /// Takes the pictures due at `t`: timed ones, then those of the events noted since the last
  /// call, in their order. The files written are added to `files`.
  void TakeDue(double t, const SnapshotSource& source, RunRecorder& recorder,
               std::vector<std::string>& files);
  /// At the run's end: renders the pictures taken for after the run; a picture that could not
  /// be written leaves `files`.
  void RenderPending(RunRecorder& recorder, std::vector<std::string>& files);

 private:
  /// A picture as taken: the joint positions of its tick, what to render, where it goes, and
  /// the workpiece as turned then (null: as the scene made it, nothing cut yet).
  struct PendingSnapshot {
    std::vector<double> joints;
    const SnapshotSpec* spec;
    std::string path;
    std::shared_ptr<const TurnedProfile> turned;
  };

 public:
  /// Which pictures are taken, due and pending: kept to go back to (a run's in-memory copy,
  /// SceneRun::Save). The renderer is a cache of the scene and stays.
  struct Saved {
    std::vector<bool> snapped;
    std::vector<int> event_shots;
    std::vector<std::pair<size_t, int>> due;
    std::vector<PendingSnapshot> pending;
    std::shared_ptr<const TurnedProfile> turned;
  };
  Saved Save() const { return {snapped_, event_shots_, due_, pending_, turned_}; }
  void Restore(const Saved& saved) {
    snapped_ = saved.snapped;
    event_shots_ = saved.event_shots;
    due_ = saved.due;
    pending_ = saved.pending;
    turned_ = saved.turned;
  }

 private:
  void Take(const SnapshotSpec& s, const std::string& file, nlohmann::ordered_json event,
            const SnapshotSource& source, RunRecorder& recorder, std::vector<std::string>& files);
  std::shared_ptr<const TurnedProfile> TurnedNow(const SnapshotSource& source);
  /// Returns whether the picture was written (a failure is a write error of the run).
  bool Render(const PendingSnapshot& shot, RunRecorder& recorder);

  const Scene* scene_;
  SnapshotSettings settings_;
  std::unique_ptr<SceneRenderer> renderer_;  ///< made at the first picture
  std::vector<bool> snapped_;                ///< per timed snapshot: taken
  std::vector<int> event_shots_;             ///< per snapshot: occurrences of its event so far
  /// Event snapshots due at this tick's pictures: snapshot index and occurrence (1, 2, ...).
  std::vector<std::pair<size_t, int>> due_;
  std::vector<PendingSnapshot> pending_;  ///< taken, rendered after the run
  /// The turned stock as the last picture took it: shared by the pictures until the next cut.
  std::shared_ptr<const TurnedProfile> turned_;
};

}  // namespace vmt::sim
