#include "sim/scene/snapshot_loader.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {
namespace {

// Event snapshots name their files themselves, one per occurrence; a limit keeps a scene with
// many latches (a measuring cycle) from writing a picture for each by mistake.
constexpr int kMaxEventSnapshots = 100;

SnapshotEvent ReadEvent(const YamlNode& n) {
  for (SnapshotEvent e :
       {SnapshotEvent::kCollision, SnapshotEvent::kProbeLatch, SnapshotEvent::kError})
    if (n.String() == ToString(e)) return e;
  n.Fail("expected collision, probe_latch or error, got '" + n.String() + "'");
}

void RequirePlainFileName(const YamlNode& where, const std::string& file) {
  if (file.empty() || file.find('/') != std::string::npos || file.find("..") != std::string::npos)
    where.Fail("a plain file name inside the output folder");
}

// `mask:`, `allowed_fraction:`, `tolerance_levels:`: what a golden comparison of the picture
// leaves out and tolerates; the rectangles lie within the picture.
void ReadComparison(const YamlNode& n, SnapshotSpec& spec) {
  if (n.Has("mask")) {
    const YamlNode list = n["mask"];
    if (!list.IsSequence()) list.Fail("expected a list of [x, y, width, height] rectangles");
    for (size_t j = 0; j < list.size(); ++j) {
      const YamlNode r = list[j];
      if (!r.IsSequence() || r.size() != 4) r.Fail("expected [x, y, width, height] in pixels");
      const SnapshotMaskRect rect{r[0].Int(), r[1].Int(), r[2].Int(), r[3].Int()};
      if (rect.x < 0 || rect.y < 0) r.Fail("x and y must be >= 0 (the top left corner is 0, 0)");
      if (rect.width < 1 || rect.height < 1) r.Fail("width and height must be >= 1");
      if (rect.x + rect.width > spec.width || rect.y + rect.height > spec.height)
        r.Fail("reaches beyond the " + std::to_string(spec.width) + "x" +
               std::to_string(spec.height) + " picture");
      spec.mask.push_back(rect);
    }
  }
  if (n.Has("allowed_fraction")) {
    const double f = n["allowed_fraction"].Double(0, 1);
    if (!(f >= 0 && f <= 1))
      n["allowed_fraction"].Fail("must be in 0..1 (a fraction of the pixels, 0.001 = 0.1 %)");
    spec.allowed_fraction = f;
  }
  if (n.Has("tolerance_levels")) {
    const int levels = n["tolerance_levels"].Int(0, 255);
    if (levels < 0 || levels > 255) n["tolerance_levels"].Fail("must be in 0..255");
    spec.tolerance_levels = levels;
  }
}

// A series' file for its index-th picture (1-based) at time t: `{i}` (the index, zero-padded
// to the width of the count) and `{t}` (the time in s) replaced; a name without them is a
// prefix to which the time is appended, as a single snapshot's default name.
std::string SeriesFile(const std::string& pattern, int index, int count, double t) {
  if (pattern.find('{') == std::string::npos) return pattern + Fmt(t) + "s.png";
  std::string i = std::to_string(index);
  i.insert(0, std::to_string(count).size() - i.size(), '0');
  std::string out;
  for (size_t p = 0; p < pattern.size();) {
    if (pattern.compare(p, 3, "{i}") == 0) {
      out += i, p += 3;
    } else if (pattern.compare(p, 3, "{t}") == 0) {
      out += Fmt(t), p += 3;
    } else {
      out += pattern[p++];
    }
  }
  return out;
}

// `every:`, `from:`, `to:`: the times of a series, from `from` in steps of `every` up to `to`
// (included when a step lands on it).
std::vector<double> SeriesTimes(const YamlNode& n) {
  if (!n.Has("to")) n.Fail("a series (every:) needs to: (the last time, s)");
  const double every = n["every"].Double();
  const double from = n.Double("from", 0);
  const double to = n["to"].Double();
  if (!(every > 0)) n["every"].Fail("must be > 0 s");
  if (!(from >= 0)) n["from"].Fail("must be >= 0 s");
  if (!(from <= to)) n["to"].Fail("must be >= from (" + Fmt(from) + " s)");
  const double steps = std::floor((to - from) / every + 1e-9);
  if (steps + 1 > kMaxSeriesPictures)
    n["every"].Fail("gives " + Fmt(steps + 1) + " pictures from " + Fmt(from) + " to " + Fmt(to) +
                    " s; a series has at most " + std::to_string(kMaxSeriesPictures));
  std::vector<double> times;
  for (int k = 0; k <= int(steps); ++k) times.push_back(from + k * every);
  return times;
}

}  // namespace

const char* ToString(SnapshotEvent e) {
  switch (e) {
    case SnapshotEvent::kNone:
      return "none";
    case SnapshotEvent::kCollision:
      return "collision";
    case SnapshotEvent::kProbeLatch:
      return "probe_latch";
    case SnapshotEvent::kError:
      return "error";
  }
  return "none";
}

void ReadSnapshots(const YamlNode& list, Scene& scene) {
  std::vector<SnapshotSpec>& specs = scene.snapshots;
  std::set<std::string> files;  // every file a snapshot or a contact sheet writes
  auto claim = [&files](const YamlNode& where, const std::string& file) {
    if (!files.insert(file).second)
      where.Fail("'" + file + "' is written by an earlier snapshot already");
  };
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlNode n = list[i];
    n.AllowKeys({"at", "on", "limit", "every", "from", "to", "sheet", "camera", "width", "height",
                 "file", "mask", "allowed_fraction", "tolerance_levels"});
    const int kinds = int(n.Has("at")) + int(n.Has("on")) + int(n.Has("every"));
    if (kinds == 0)
      n.Fail("needs at: (a time, s), every: (a series) or on: (collision, probe_latch or error)");
    SnapshotSpec spec;
    spec.camera = n["camera"].String();
    if (!scene.Camera(spec.camera)) n["camera"].Fail("no camera '" + spec.camera + "'");
    spec.width = n.Int("width", 640, 16, 4096);
    spec.height = n.Int("height", 480, 16, 4096);
    if (spec.width < 16 || spec.width > 4096) n["width"].Fail("must be in 16..4096");
    if (spec.height < 16 || spec.height > 4096) n["height"].Fail("must be in 16..4096");
    ReadComparison(n, spec);
    if (n.Has("on")) {
      if (n.Has("at")) n["at"].Fail("a snapshot is taken at a time or on an event, not both");
      if (n.Has("every")) n["every"].Fail("a snapshot is a series or on an event, not both");
      if (n.Has("file")) n["file"].Fail("an event snapshot names its files itself");
      spec.on = ReadEvent(n["on"]);
      spec.limit = n.Int("limit", 1, 1, kMaxEventSnapshots);
      if (spec.limit < 1 || spec.limit > kMaxEventSnapshots)
        n["limit"].Fail("must be in 1.." + std::to_string(kMaxEventSnapshots));
      // Two entries for the same event and camera would write the same files.
      for (const SnapshotSpec& other : specs)
        if (other.on == spec.on && other.camera == spec.camera)
          n["on"].Fail(std::string("a second snapshot on ") + ToString(spec.on) + " with camera '" +
                       spec.camera + "'");
      specs.push_back(spec);
      continue;
    }
    if (n.Has("limit")) n["limit"].Fail("only with on:");
    if (n.Has("every")) {
      if (n.Has("at")) n["at"].Fail("a snapshot is taken at a time or a series, not both");
      const std::vector<double> times = SeriesTimes(n);
      const std::string pattern = n.String("file", spec.camera + "_");
      if (pattern.find('{') == std::string::npos && pattern.size() >= 4 &&
          pattern.compare(pattern.size() - 4, 4, ".png") == 0)
        n["file"].Fail(
            "a series names its pictures with {i} (1, 2, ...) or {t} (the time), or "
            "takes a prefix without .png, e.g. turn-{i}.png or turn_");
      const std::string stem = pattern.substr(0, pattern.find('{'));
      SnapshotSeries series;
      series.sheet = n.String("sheet", stem + "sheet.png");
      RequirePlainFileName(n.Has("sheet") ? n["sheet"] : n, series.sheet);
      spec.series = int(scene.snapshot_series.size());
      for (size_t k = 0; k < times.size(); ++k) {
        spec.at_s = times[k];
        spec.file = SeriesFile(pattern, int(k + 1), int(times.size()), times[k]);
        RequirePlainFileName(n.Has("file") ? n["file"] : n, spec.file);
        claim(n.Has("file") ? n["file"] : n, spec.file);
        series.shots.push_back(specs.size());
        specs.push_back(spec);
      }
      claim(n.Has("sheet") ? n["sheet"] : n, series.sheet);
      scene.snapshot_series.push_back(std::move(series));
      continue;
    }
    for (const char* key : {"from", "to", "sheet"})
      if (n.Has(key)) n[key].Fail("only with every: (a series)");
    spec.at_s = n["at"].Double(0, kMaxSceneSeconds);
    std::ostringstream file;
    file << spec.camera << "_" << Fmt(spec.at_s) << "s.png";
    spec.file = n.String("file", file.str());
    RequirePlainFileName(n.Has("file") ? n["file"] : n, spec.file);
    claim(n.Has("file") ? n["file"] : n, spec.file);
    specs.push_back(spec);
  }
}

}  // namespace vmt::sim
