// The scene's `snapshots:`: pictures at a time keep their names; pictures on an event (a
// collision, a probe latch, an NC error) take a limit; every bad entry names the YAML path.

#include "sim/scene/snapshot_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

std::string WriteScene(const std::string& name, const std::string& snapshots) {
  return testing::WriteLatheScene("snapshot_loader", name,
                                  "duration: 0.01\nsnapshots:\n" + snapshots);
}

std::string ErrorOf(const std::string& name, const std::string& snapshots) {
  return testing::SceneLoadError(WriteScene(name, snapshots));
}

TEST(SnapshotLoaderTest, TimesAndEvents) {
  const Scene s =
      LoadScene(WriteScene("good",
                           "  - {at: 1.5, camera: iso}\n"
                           "  - {on: collision, camera: work, width: 320, height: 240}\n"
                           "  - {on: probe_latch, camera: work, limit: 4}\n"
                           "  - {on: error, camera: iso}\n"));
  ASSERT_EQ(s.snapshots.size(), 4u);
  EXPECT_EQ(s.snapshots[0].on, SnapshotEvent::kNone);
  EXPECT_EQ(s.snapshots[0].file, "iso_1.5s.png");
  EXPECT_EQ(s.snapshots[1].on, SnapshotEvent::kCollision);
  EXPECT_EQ(s.snapshots[1].limit, 1);  // the first occurrence unless told
  EXPECT_EQ(s.snapshots[1].width, 320);
  EXPECT_EQ(s.snapshots[2].on, SnapshotEvent::kProbeLatch);
  EXPECT_EQ(s.snapshots[2].limit, 4);
  EXPECT_EQ(s.snapshots[3].on, SnapshotEvent::kError);
  EXPECT_EQ(s.snapshots[3].file, "");  // named per occurrence by the runner
}

TEST(SnapshotLoaderTest, BadEntriesNameTheirPath) {
  EXPECT_THAT(ErrorOf("neither", "  - {camera: iso}\n"),
              HasSubstr("snapshots[0]: needs at: (a time, s) or on:"));
  EXPECT_THAT(ErrorOf("both", "  - {at: 1, on: error, camera: iso}\n"),
              HasSubstr("snapshots[0].at: a snapshot is taken at a time or on an event"));
  EXPECT_THAT(ErrorOf("bad_event", "  - {on: crash, camera: iso}\n"),
              HasSubstr("snapshots[0].on: expected collision, probe_latch or error, got 'crash'"));
  EXPECT_THAT(ErrorOf("event_file", "  - {on: error, camera: iso, file: e.png}\n"),
              HasSubstr("snapshots[0].file: an event snapshot names its files itself"));
  EXPECT_THAT(ErrorOf("limit_zero", "  - {on: error, camera: iso, limit: 0}\n"),
              HasSubstr("snapshots[0].limit: must be in 1..100"));
  EXPECT_THAT(ErrorOf("limit_at", "  - {at: 1, camera: iso, limit: 2}\n"),
              HasSubstr("snapshots[0].limit: only with on:"));
  EXPECT_THAT(ErrorOf("twice", "  - {on: error, camera: iso}\n  - {on: error, camera: iso}\n"),
              HasSubstr("snapshots[1].on: a second snapshot on error with camera 'iso'"));
  EXPECT_THAT(ErrorOf("event_camera", "  - {on: error, camera: nope}\n"),
              HasSubstr("snapshots[0].camera: no camera 'nope'"));
  EXPECT_EQ(
      ErrorOf("other_camera", "  - {on: error, camera: iso}\n  - {on: error, camera: work}\n"), "");
}

}  // namespace
}  // namespace vmt::sim
