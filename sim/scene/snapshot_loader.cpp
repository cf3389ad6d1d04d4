#include "sim/scene/snapshot_loader.hpp"

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

std::vector<SnapshotSpec> ReadSnapshots(const YamlNode& list, const Scene& scene) {
  std::vector<SnapshotSpec> specs;
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlNode n = list[i];
    n.AllowKeys({"at", "on", "limit", "camera", "width", "height", "file"});
    if (!n.Has("at") && !n.Has("on"))
      n.Fail("needs at: (a time, s) or on: (collision, probe_latch or error)");
    SnapshotSpec spec;
    spec.camera = n["camera"].String();
    if (!scene.Camera(spec.camera)) n["camera"].Fail("no camera '" + spec.camera + "'");
    spec.width = n.Int("width", 640);
    spec.height = n.Int("height", 480);
    if (spec.width < 16 || spec.width > 4096) n["width"].Fail("must be in 16..4096");
    if (spec.height < 16 || spec.height > 4096) n["height"].Fail("must be in 16..4096");
    if (n.Has("on")) {
      if (n.Has("at")) n["at"].Fail("a snapshot is taken at a time or on an event, not both");
      if (n.Has("file")) n["file"].Fail("an event snapshot names its files itself");
      spec.on = ReadEvent(n["on"]);
      spec.limit = n.Int("limit", 1);
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
    spec.at_s = n["at"].Double();
    std::ostringstream file;
    file << spec.camera << "_" << Fmt(spec.at_s) << "s.png";
    spec.file = n.String("file", file.str());
    if (spec.file.find('/') != std::string::npos || spec.file.find("..") != std::string::npos)
      n["file"].Fail("a plain file name inside the output folder");
    specs.push_back(spec);
  }
  return specs;
}

}  // namespace vmt::sim
