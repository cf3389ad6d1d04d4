// The run's pictures on their own: a timed one once at its time, an event's up to its limit in
// the order the events came, each announced as a "snapshot" event with its file; after the run
// (SnapshotSettings::after_run) the files are listed at once and written by RenderPending.
#include "sim/runner/run_snapshots.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "sim/runner/make_backend.hpp"

namespace vmt::sim {
namespace {

Scene PicturedScene() {
  Scene scene = LoadScene(testing::SourcePath("scenes/measure-move-collision.yaml"));
  scene.snapshots.clear();
  SnapshotSpec timed;
  timed.at_s = 0.5;
  timed.file = "timed.png";
  SnapshotSpec collision;
  collision.on = SnapshotEvent::kCollision;
  collision.limit = 2;
  for (SnapshotSpec* s : {&timed, &collision}) {
    s->camera = "work";
    s->width = 48;
    s->height = 36;
    scene.snapshots.push_back(*s);
  }
  return scene;
}

const nlohmann::ordered_json kCollision = {{"event", "path_guard"}, {"clear", false}};

TEST(RunSnapshots, TimedOnceAndEventsUpToTheirLimit) {
  const Scene scene = PicturedScene();
  SnapshotSettings options;
  options.out_dir = testing::OutputDir("run_snapshots/at_once");
  const auto backend = MakeBackend(BackendKind::kKinematic, *scene.model, scene.initial);
  RunRecorder recorder;
  recorder.Open(options.out_dir);
  std::vector<nlohmann::ordered_json> events;
  recorder.AddObserver([&events](const nlohmann::ordered_json& e) { events.push_back(e); });
  RunSnapshots snapshots(scene, options);
  std::vector<std::string> files;

  snapshots.TakeDue(0.25, {*backend}, recorder, files);
  EXPECT_TRUE(files.empty());
  for (int i = 0; i < 3; ++i) snapshots.NoteEvent(kCollision);
  snapshots.NoteEvent({{"event", "path_guard"}, {"clear", true}});  // no collision
  snapshots.TakeDue(0.5, {*backend}, recorder, files);
  ASSERT_EQ(files.size(), 3u);  // the timed one, then two of the three collisions
  EXPECT_EQ(files[0], options.out_dir + "/timed.png");
  for (const std::string& f : files) EXPECT_TRUE(std::filesystem::exists(f)) << f;
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0]["file"], "timed.png");
  EXPECT_EQ(events[1]["on"], "collision");
  EXPECT_EQ(events[2]["n"], 2);
  snapshots.NoteEvent(kCollision);  // beyond the limit
  snapshots.TakeDue(0.75, {*backend}, recorder, files);
  EXPECT_EQ(files.size(), 3u);
}

TEST(RunSnapshots, AfterTheRunTheyAreWrittenAtTheEnd) {
  const Scene scene = PicturedScene();
  SnapshotSettings options;
  options.out_dir = testing::OutputDir("run_snapshots/after_run");
  options.after_run = true;
  std::filesystem::remove(options.out_dir + "/timed.png");
  const auto backend = MakeBackend(BackendKind::kKinematic, *scene.model, scene.initial);
  RunRecorder recorder;
  recorder.Open(options.out_dir);
  RunSnapshots snapshots(scene, options);
  std::vector<std::string> files;
  snapshots.TakeDue(0.5, {*backend}, recorder, files);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_FALSE(std::filesystem::exists(files[0]));
  snapshots.RenderPending(recorder, files);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(files[0]));
}

}  // namespace
}  // namespace vmt::sim
