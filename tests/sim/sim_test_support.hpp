#pragma once
// Shared by the sim tests: the lathe model (loaded once) and a small driver that commands drives
// and steps a backend.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "sim/kinematic/kinematic_backend.hpp"
#include "sim/model/model_error.hpp"
#include "sim/physics/physics_backend.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {
inline void PrintTo(BackendKind k, std::ostream* os) { *os << ToString(k); }
}  // namespace vmt::sim

namespace vmt::sim::testing {

inline std::string SourcePath(const std::string& relative) {
  return (std::filesystem::path(VMT_SOURCE_DIR) / relative).string();
}

inline std::string OutputDir(const std::string& name) {
  const auto dir = std::filesystem::path(VMT_BINARY_DIR) / "test_output" / "sim" / name;
  std::filesystem::create_directories(dir);
  return dir.string();
}

/// A whole file as bytes ("" if missing).
inline std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A scene file on lathe-c1 for the loader tests: test_output/sim/<folder>/<name>.yaml holding
/// the scene's name, the model and then `body`, the rest of its YAML.
inline std::string WriteLatheScene(const std::string& folder, const std::string& name,
                                   const std::string& body) {
  const std::string path = OutputDir(folder) + "/" + name + ".yaml";
  std::ofstream(path) << "scene: " << name
                      << "\nmodel: " << SourcePath("models/lathe-c1/machine.yaml") << "\n"
                      << body;
  return path;
}

/// What loading the scene file throws, "" if it loads.
inline std::string SceneLoadError(const std::string& path) {
  try {
    LoadScene(path);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

inline const MachineModel& Lathe() {
  static const MachineModel model = LoadMachineModel(SourcePath("models/lathe-c1/machine.yaml"));
  return model;
}

/// `s` with the first `from` replaced by `to`; fails the test if `from` is not there.
inline std::string ReplaceOnce(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture text not found: " << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

/// lathe-c1 with `edit` applied to its machine.yaml, written to a scratch folder as `name`.yaml
/// and loaded from there; the URDF and meshes stay where they are. Throws ModelError.
inline MachineModel EditedLathe(const std::string& name,
                                const std::function<std::string(std::string)>& edit) {
  std::string yaml = ReadBytes(SourcePath("models/lathe-c1/machine.yaml"));
  yaml = ReplaceOnce(yaml, "urdf: machine.urdf",
                     "urdf: " + SourcePath("models/lathe-c1/machine.urdf"));
  const std::string path = OutputDir("edited_models") + "/" + name + ".yaml";
  std::ofstream(path) << edit(yaml);
  return LoadMachineModel(path);
}

/// Commands drives of a backend directly, as the PLC/NC would through the DriveBus.
class Bench {
 public:
  explicit Bench(MachineBackend& backend) : backend_(backend) {
    const auto& m = backend.model();
    mdt_.setpoints.resize(m.drives.size());
    mdt_.outputs.assign(m.io.size(), 0);
    // Servos hold where they are, spindles stand at speed 0.
    for (size_t d = 0; d < m.drives.size(); ++d)
      mdt_.setpoints[d] = m.drives[d].spindle
                              ? control::DriveSetpoint{control::DriveMode::kVelocity, 0, 0}
                              : control::DriveSetpoint{control::DriveMode::kPosition,
                                                       backend.Read().feedback[d].position, 0};
  }
  int Drive(const std::string& name) const { return backend_.model().DriveIndex(name); }
  int Io(const std::string& name) const { return control::IndexOf(backend_.model().io, name); }
  void Command(const std::string& drive, control::DriveMode mode, double value,
               uint8_t parameter_set = 0) {
    mdt_.setpoints[Drive(drive)] = {mode, value, parameter_set};
  }
  void Output(const std::string& name, bool on) { mdt_.outputs[Io(name)] = on; }
  const control::DriveFeedback& Feedback(const std::string& drive) const {
    return backend_.Read().feedback[Drive(drive)];
  }
  bool Input(const std::string& name) const { return backend_.Read().inputs[Io(name)] != 0; }
  /// Steps for `seconds`; `each` (if given) sees every tick.
  void Run(double seconds, const std::function<void()>& each = {}) {
    const int64_t n = std::llround(seconds / kDriveTickS);
    for (int64_t i = 0; i < n; ++i) {
      backend_.Write(mdt_);
      backend_.Step();
      if (each) each();
    }
  }
  /// Steps until `done` holds or `timeout` passes; returns the time it took, or -1.
  double RunUntil(const std::function<bool()>& done, double timeout) {
    const double t0 = backend_.time_s();
    while (backend_.time_s() - t0 < timeout) {
      backend_.Write(mdt_);
      backend_.Step();
      if (done()) return backend_.time_s() - t0;
    }
    return -1;
  }
  control::MasterTelegram& mdt() { return mdt_; }

 private:
  MachineBackend& backend_;
  control::MasterTelegram mdt_;
};

}  // namespace vmt::sim::testing
