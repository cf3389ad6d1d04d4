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
              HasSubstr("snapshots[0]: needs at: (a time, s), every: (a series) or on:"));
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

TEST(SnapshotLoaderTest, MaskAndTolerance) {
  const Scene s = LoadScene(
      WriteScene("mask",
                 "  - {at: 1, camera: iso, width: 320, height: 240, mask: [[0, 0, 10, 20], "
                 "[300, 200, 20, 40]], allowed_fraction: 0.001, tolerance_levels: 4}\n"
                 "  - {at: 2, camera: iso}\n"
                 "  - {on: error, camera: iso, mask: [[1, 2, 3, 4]]}\n"));
  ASSERT_EQ(s.snapshots.size(), 3u);
  ASSERT_EQ(s.snapshots[0].mask.size(), 2u);
  EXPECT_EQ(s.snapshots[0].mask[1].x, 300);
  EXPECT_EQ(s.snapshots[0].mask[1].y, 200);
  EXPECT_EQ(s.snapshots[0].mask[1].width, 20);
  EXPECT_EQ(s.snapshots[0].mask[1].height, 40);
  EXPECT_EQ(s.snapshots[0].allowed_fraction, 0.001);
  EXPECT_EQ(s.snapshots[0].tolerance_levels, 4);
  EXPECT_TRUE(s.snapshots[1].mask.empty());
  EXPECT_FALSE(s.snapshots[1].allowed_fraction);  // the project's tolerance
  EXPECT_FALSE(s.snapshots[1].tolerance_levels);
  EXPECT_EQ(s.snapshots[2].mask.size(), 1u);
}

TEST(SnapshotLoaderTest, BadMasksAndTolerancesNameTheirPath) {
  EXPECT_THAT(ErrorOf("mask_negative", "  - {at: 1, camera: iso, mask: [[0, 0, -5, 10]]}\n"),
              HasSubstr("snapshots[0].mask[0]: width and height must be >= 1"));
  EXPECT_THAT(ErrorOf("mask_corner", "  - {at: 1, camera: iso, mask: [[-1, 0, 5, 10]]}\n"),
              HasSubstr("snapshots[0].mask[0]: x and y must be >= 0"));
  EXPECT_THAT(ErrorOf("mask_outside",
                      "  - {at: 1, camera: iso, mask: [[0, 0, 5, 5], "
                      "[630, 0, 20, 10]]}\n"),
              HasSubstr("snapshots[0].mask[1]: reaches beyond the 640x480 picture"));
  EXPECT_THAT(ErrorOf("mask_three", "  - {at: 1, camera: iso, mask: [[0, 0, 5]]}\n"),
              HasSubstr("snapshots[0].mask[0]: expected [x, y, width, height]"));
  EXPECT_THAT(ErrorOf("mask_flat", "  - {at: 1, camera: iso, mask: [0, 0, 5, 5]}\n"),
              HasSubstr("snapshots[0].mask[0]: expected [x, y, width, height]"));
  EXPECT_THAT(ErrorOf("fraction", "  - {at: 1, camera: iso, allowed_fraction: 1.5}\n"),
              HasSubstr("snapshots[0].allowed_fraction: must be in 0..1"));
  EXPECT_THAT(ErrorOf("fraction_neg", "  - {at: 1, camera: iso, allowed_fraction: -0.1}\n"),
              HasSubstr("snapshots[0].allowed_fraction: must be in 0..1"));
  EXPECT_THAT(ErrorOf("levels", "  - {at: 1, camera: iso, tolerance_levels: 300}\n"),
              HasSubstr("snapshots[0].tolerance_levels: must be in 0..255"));
  EXPECT_THAT(ErrorOf("same_file", "  - {at: 1, camera: iso}\n  - {at: 1, camera: iso}\n"),
              HasSubstr("snapshots[1]: 'iso_1s.png' is written by an earlier snapshot"));
}

TEST(SnapshotLoaderTest, SeriesNamesItsPicturesAndSheet) {
  const Scene s = LoadScene(
      WriteScene("series",
                 "  - {every: 0.25, from: 2, to: 3, camera: iso, width: 64, height: 48}\n"
                 "  - {every: 1, to: 10, camera: work, file: \"turn-{i}.png\", "
                 "mask: [[0, 0, 4, 4]]}\n"
                 "  - {every: 0.5, from: 1, to: 1.9, camera: iso, file: \"z{t}.png\", sheet: "
                 "zs.png}\n"
                 "  - {every: 2, from: 0, to: 1, camera: work, file: top_}\n"));
  ASSERT_EQ(s.snapshot_series.size(), 4u);
  ASSERT_EQ(s.snapshot_series[0].shots.size(), 5u);  // 2, 2.25, ..., 3: both ends
  EXPECT_EQ(s.snapshot_series[0].sheet, "iso_sheet.png");
  const SnapshotSpec& first = s.snapshots[s.snapshot_series[0].shots[0]];
  const SnapshotSpec& last = s.snapshots[s.snapshot_series[0].shots[4]];
  EXPECT_EQ(first.file, "iso_2s.png");
  EXPECT_DOUBLE_EQ(first.at_s, 2);
  EXPECT_EQ(first.width, 64);
  EXPECT_EQ(first.series, 0);
  EXPECT_EQ(s.snapshots[s.snapshot_series[0].shots[1]].file, "iso_2.25s.png");
  EXPECT_EQ(last.file, "iso_3s.png");
  // {i} counts from 1, zero-padded to the width of the count (11 pictures: 01..11).
  ASSERT_EQ(s.snapshot_series[1].shots.size(), 11u);
  EXPECT_EQ(s.snapshots[s.snapshot_series[1].shots[0]].file, "turn-01.png");
  EXPECT_EQ(s.snapshots[s.snapshot_series[1].shots[10]].file, "turn-11.png");
  EXPECT_DOUBLE_EQ(s.snapshots[s.snapshot_series[1].shots[10]].at_s, 10);
  EXPECT_EQ(s.snapshots[s.snapshot_series[1].shots[3]].mask.size(), 1u);
  EXPECT_EQ(s.snapshot_series[1].sheet, "turn-sheet.png");
  // to: is reached only when a step lands on it.
  ASSERT_EQ(s.snapshot_series[2].shots.size(), 2u);
  EXPECT_EQ(s.snapshots[s.snapshot_series[2].shots[1]].file, "z1.5.png");
  EXPECT_EQ(s.snapshot_series[2].sheet, "zs.png");
  ASSERT_EQ(s.snapshot_series[3].shots.size(), 1u);
  EXPECT_EQ(s.snapshots[s.snapshot_series[3].shots[0]].file, "top_0s.png");
  EXPECT_EQ(s.snapshot_series[3].sheet, "top_sheet.png");
  EXPECT_EQ(s.snapshots.size(), 5u + 11u + 2u + 1u);
}

TEST(SnapshotLoaderTest, BadSeriesNameTheirPath) {
  EXPECT_THAT(ErrorOf("every_zero", "  - {every: 0, to: 2, camera: iso}\n"),
              HasSubstr("snapshots[0].every: must be > 0 s"));
  EXPECT_THAT(ErrorOf("every_negative", "  - {every: -1, to: 2, camera: iso}\n"),
              HasSubstr("snapshots[0].every: must be > 0 s"));
  EXPECT_THAT(ErrorOf("backwards", "  - {every: 1, from: 5, to: 2, camera: iso}\n"),
              HasSubstr("snapshots[0].to: must be >= from (5 s)"));
  EXPECT_THAT(ErrorOf("no_to", "  - {every: 1, camera: iso}\n"),
              HasSubstr("snapshots[0]: a series (every:) needs to:"));
  EXPECT_THAT(ErrorOf("too_many", "  - {every: 0.001, from: 0, to: 10, camera: iso}\n"),
              HasSubstr("snapshots[0].every: gives 10001 pictures from 0 to 10 s; a series has "
                        "at most 200"));
  EXPECT_THAT(ErrorOf("series_at", "  - {every: 1, to: 2, at: 1, camera: iso}\n"),
              HasSubstr("snapshots[0].at: a snapshot is taken at a time or a series"));
  EXPECT_THAT(ErrorOf("series_on", "  - {every: 1, to: 2, on: error, camera: iso}\n"),
              HasSubstr("snapshots[0].every: a snapshot is a series or on an event"));
  EXPECT_THAT(ErrorOf("from_alone", "  - {at: 1, from: 0, camera: iso}\n"),
              HasSubstr("snapshots[0].from: only with every:"));
  EXPECT_THAT(ErrorOf("png_no_index", "  - {every: 1, to: 2, camera: iso, file: a.png}\n"),
              HasSubstr("snapshots[0].file: a series names its pictures with {i}"));
  EXPECT_THAT(ErrorOf("sheet_path", "  - {every: 1, to: 2, camera: iso, sheet: ../s.png}\n"),
              HasSubstr("snapshots[0].sheet: a plain file name"));
  EXPECT_THAT(ErrorOf("clash", "  - {at: 2, camera: iso}\n  - {every: 1, to: 2, camera: iso}\n"),
              HasSubstr("snapshots[1]: 'iso_2s.png' is written by an earlier snapshot"));
  EXPECT_THAT(ErrorOf("same_t",
                      "  - {every: 1, to: 2, camera: iso, file: \"a{t}.png\"}\n"
                      "  - {every: 1, to: 2, camera: iso, file: \"a{i}.png\"}\n"),
              HasSubstr("snapshots[1].file: 'a1.png' is written by an earlier snapshot"));
}

}  // namespace
}  // namespace vmt::sim
