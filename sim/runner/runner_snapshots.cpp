// Pictures of a scene run: at a time or on an event, rendered at once or after the run.
#include <string_view>

#include "common/output_file.hpp"
#include "render/image.hpp"
#include "sim/runner/event_snapshots.hpp"
#include "sim/runner/runner_state.hpp"

namespace vmt::sim {

// An event snapshot is due for each of the scene's `on:` snapshots of this event that has not
// reached its limit.
void SceneRun::State::NoteSnapshotEvent(const nlohmann::ordered_json& event) {
  if (!options.snapshots) return;
  const SnapshotEvent kind = SnapshotEventOf(event);
  if (kind == SnapshotEvent::kNone) return;
  for (size_t i = 0; i < scene.snapshots.size(); ++i)
    if (scene.snapshots[i].on == kind && event_shots[i] < scene.snapshots[i].limit)
      pending_shots.emplace_back(i, ++event_shots[i]);
}

// The machine as it stands at this tick, written to `file` with its `snapshot` event.
void SceneRun::State::TakeSnapshot(const SnapshotSpec& s, const std::string& file,
                                   nlohmann::ordered_json event) {
  if (!options.snapshots) return;
  PendingSnapshot shot{backend->JointPositions(), &s, options.out_dir + "/" + file, TurnedNow()};
  if (!options.snapshots_after_run) {
    if (!RenderSnapshot(shot)) return;
  } else if (recorder.writing()) {
    pending_snapshots.push_back(std::move(shot));
  }
  if (!recorder.writing()) return;
  result.snapshot_files.push_back(options.out_dir + "/" + file);
  event["file"] = file;
  recorder.Event(std::move(event));
}

// The stock cutter's profile for a picture of this tick, copied only when a cut has changed it
// since the last picture. Finer than PathGuard's, as the web station draws it: to a micrometre.
std::shared_ptr<const TurnedProfile> SceneRun::State::TurnedNow() {
  if (!cutter || stock_cuts == 0) return nullptr;
  if (!turned_profile || turned_profile->version != stock_cuts)
    turned_profile = std::make_shared<const TurnedProfile>(
        TurnedProfile{stock_cuts, cutter->stock().Cylinders(1e-6)});
  return turned_profile;
}

bool SceneRun::State::RenderSnapshot(const PendingSnapshot& shot) {
  if (!renderer) renderer = std::make_unique<SceneRenderer>(m, scene.workpiece);
  const SnapshotSpec& s = *shot.spec;
  const render::Image picture =
      renderer->Render(shot.joints, *scene.Camera(s.camera), s.width, s.height, shot.turned.get());
  if (!recorder.writing()) return true;
  try {
    render::WritePng(shot.path, picture);
    return true;
  } catch (const common::WriteError& e) {
    recorder.AddWriteError(e.what());
    return false;
  }
}

void SceneRun::State::RenderPendingSnapshots() {
  for (const PendingSnapshot& shot : pending_snapshots)
    if (!RenderSnapshot(shot)) std::erase(result.snapshot_files, shot.path);
  pending_snapshots.clear();
}

bool SceneRun::State::WriteOutput(const std::string& path, std::string_view text) {
  try {
    common::WriteFileAtomically(path, text);
    return true;
  } catch (const common::WriteError& e) {
    recorder.AddWriteError(e.what());
    return false;
  }
}

}  // namespace vmt::sim
