#include "sim/runner/run_snapshots.hpp"

#include "common/output_file.hpp"
#include "render/image.hpp"
#include "sim/runner/event_snapshots.hpp"

namespace vmt::sim {

RunSnapshots::RunSnapshots(const Scene& scene, SnapshotSettings settings)
    : scene_(&scene),
      settings_(std::move(settings)),
      snapped_(scene.snapshots.size(), false),
      event_shots_(scene.snapshots.size(), 0) {}

// An event snapshot is due for each of the scene's `on:` snapshots of this event that has not
// reached its limit.
void RunSnapshots::NoteEvent(const nlohmann::ordered_json& event) {
  if (!settings_.take) return;
  const SnapshotEvent kind = SnapshotEventOf(event);
  if (kind == SnapshotEvent::kNone) return;
  for (size_t i = 0; i < scene_->snapshots.size(); ++i)
    if (scene_->snapshots[i].on == kind && event_shots_[i] < scene_->snapshots[i].limit)
      due_.emplace_back(i, ++event_shots_[i]);
}

void RunSnapshots::TakeDue(double t, const SnapshotSource& source, RunRecorder& recorder,
                           std::vector<std::string>& files) {
  for (size_t i = 0; i < scene_->snapshots.size(); ++i) {
    const SnapshotSpec& s = scene_->snapshots[i];
    if (s.on != SnapshotEvent::kNone || snapped_[i] || t < s.at_s - 1e-9) continue;
    snapped_[i] = true;
    Take(s, s.file, {{"t", t}, {"event", "snapshot"}, {"camera", s.camera}}, source, recorder,
         files);
  }
  // Events recorded since the last pictures (this tick's, and a stylus' over-travel found in
  // the last physics step), in the order they came.
  for (const auto& [i, n] : std::exchange(due_, {})) {
    const SnapshotSpec& s = scene_->snapshots[i];
    Take(s, EventSnapshotFile(s, n, t),
         {{"t", t}, {"event", "snapshot"}, {"on", ToString(s.on)}, {"n", n}, {"camera", s.camera}},
         source, recorder, files);
  }
}

// The machine as it stands at this tick, written to `file` with its `snapshot` event.
void RunSnapshots::Take(const SnapshotSpec& s, const std::string& file,
                        nlohmann::ordered_json event, const SnapshotSource& source,
                        RunRecorder& recorder, std::vector<std::string>& files) {
  if (!settings_.take) return;
  const std::string path = settings_.out_dir + "/" + file;
  PendingSnapshot shot{source.backend.JointPositions(), &s, path, TurnedNow(source)};
  if (!settings_.after_run) {
    if (!Render(shot, recorder)) return;
  } else if (recorder.writing()) {
    pending_.push_back(std::move(shot));
  }
  if (!recorder.writing()) return;
  files.push_back(path);
  event["file"] = file;
  recorder.Event(std::move(event));
}

// The stock cutter's profile for a picture of this tick, copied only when a cut has changed it
// since the last picture. Finer than PathGuard's, as the web station draws it: to a micrometre.
std::shared_ptr<const TurnedProfile> RunSnapshots::TurnedNow(const SnapshotSource& source) {
  if (!source.cutter || source.stock_cuts == 0) return nullptr;
  if (!turned_ || turned_->version != source.stock_cuts)
    turned_ = std::make_shared<const TurnedProfile>(
        TurnedProfile{source.stock_cuts, source.cutter->stock().Cylinders(1e-6)});
  return turned_;
}

bool RunSnapshots::Render(const PendingSnapshot& shot, RunRecorder& recorder) {
  if (!renderer_) renderer_ = std::make_unique<SceneRenderer>(*scene_->model, scene_->workpiece);
  const SnapshotSpec& s = *shot.spec;
  const render::Image picture = renderer_->Render(shot.joints, *scene_->Camera(s.camera), s.width,
                                                  s.height, shot.turned.get());
  if (!recorder.writing()) return true;
  try {
    render::WritePng(shot.path, picture);
    return true;
  } catch (const common::WriteError& e) {
    recorder.AddWriteError(e.what());
    return false;
  }
}

void RunSnapshots::RenderPending(RunRecorder& recorder, std::vector<std::string>& files) {
  for (const PendingSnapshot& shot : pending_)
    if (!Render(shot, recorder)) std::erase(files, shot.path);
  pending_.clear();
}

}  // namespace vmt::sim
