#include "sim/runner/contact_sheets.hpp"

#include <algorithm>

#include "render/contact_sheet.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {

std::vector<std::string> WriteContactSheets(const Scene& scene, const std::string& out_dir,
                                            const std::vector<std::string>& written) {
  std::vector<std::string> sheets;
  for (size_t k = 0; k < scene.snapshot_series.size(); ++k) {
    const SnapshotSeries& series = scene.snapshot_series[k];
    std::vector<render::Image> pictures;
    std::vector<std::string> captions;
    for (size_t shot : series.shots) {
      // A caller that replaced the scene's snapshots (a study's case) leaves series that are
      // not its pictures any more.
      if (shot >= scene.snapshots.size() || scene.snapshots[shot].series != int(k)) continue;
      const SnapshotSpec& s = scene.snapshots[shot];
      const std::string path = out_dir + "/" + s.file;
      if (std::find(written.begin(), written.end(), path) == written.end()) continue;
      pictures.push_back(render::ReadPng(path));
      captions.push_back(Fmt(s.at_s) + " s");
    }
    if (pictures.empty()) continue;
    const std::string path = out_dir + "/" + series.sheet;
    render::WritePng(path, render::ContactSheet(pictures, captions));
    sheets.push_back(path);
  }
  return sheets;
}

}  // namespace vmt::sim
