#pragma once
// vmt view: the operator station over a finished run (the output folder of vmt run or vmt
// serve, or a study case's saved run). The run is simulated again from its scene and its
// operator's inputs (summary.json's scene_file and backend, operator.yaml; a case's case.json):
// vmt is deterministic, so that is the run as it was, and the page can go to any time (a
// slider, an event), play at 0.1x to 10x or step. The events listed are the recorded ones
// (events.jsonl). Once the replay reaches the end its trace digest is compared with the
// recorded one; a difference (the scene or the model changed since) is reported, not hidden.
//
// Given a study folder, it serves the study's report, each case a link to its replay
// (sim/station/study_index.hpp).

#include <string>

namespace vmt::sim {

struct ViewOptions {
  std::string out_dir;
  std::string http = "127.0.0.1:8080";  ///< HOST:PORT; port 0 picks a free one
  std::string http_token;
};

/// Serves until SIGINT or SIGTERM; returns 0. Throws std::invalid_argument for a folder that is
/// neither a run's output nor a study's, and what LoadScene throws for its scene.
int View(const ViewOptions& options);

}  // namespace vmt::sim
