#include "sim/runner/contact_sheets.hpp"

#include <algorithm>

#include "render/contact_sheet.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {

std::vector<std::string> WriteContactSheets(const Scene& scene, const std::string& out_dir,
                                            const std::vector<std::string>& written) {
  std::vector<std::string> sheets;
  for (const SnapshotSeries& series : scene.snapshot_series) {
    std::vector<render::Image> pictures;
    std::vector<std::string> captions;
    for (size_t shot : series.shots) {
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
