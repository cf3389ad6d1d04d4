#pragma once
// vmt serve: a scene with its PLC outside, over Modbus TCP. In lockstep the external PLC steps
// the simulation one PLC cycle per write of the cycle register; in real time the simulation
// runs against the wall clock and reports how late its cycles were.

#include <string>

namespace vmt::sim {

struct ServeOptions {
  std::string scene;
  std::string endpoint = "127.0.0.1:5020";  ///< HOST:PORT; port 0 picks a free one
  bool lockstep = true;                     ///< else real time
  double until_s = 0;                       ///< 0: the scene's duration
  std::string out_dir = "out";
};

/// Serves until the scene's end; returns the exit code (0 ok, 1 failed expectations). Throws
/// on bad input (scene, endpoint) and when it cannot listen.
int Serve(const ServeOptions& options);

}  // namespace vmt::sim
