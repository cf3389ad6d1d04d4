#pragma once
// The machine model: built once from machine.urdf + machine.yaml, read-only afterwards
// (MuJoCo's mjModel). Internal unit is SI (m, rad, kg, s); every interface to the user and to the
// control kernel speaks machine units (mm, degrees), converted at the boundary.

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "render/mesh.hpp"
#include "sim/model/named_camera.hpp"
#include "sim/model/nc_machine_data.hpp"
#include "sim/model/probe_stylus.hpp"

namespace vmt::sim {

inline constexpr double kMmPerM = 1000.0;
inline constexpr double kDegPerRad = 57.295779513082320876798;

/// A URDF <box>, <cylinder> or <sphere>, centred on its element's origin (a cylinder along z).
/// The element's mesh is made from it for the pictures; PathGuard takes the solid itself.
struct Primitive {
  enum class Kind { kNone, kBox, kCylinder, kSphere };
  Kind kind = Kind::kNone;
  Eigen::Vector3d box_m = Eigen::Vector3d::Zero();  ///< a box's sides
  double radius_m = 0, length_m = 0;                ///< a cylinder's; a sphere's radius
};

struct Visual {
  std::string name;                          ///< the URDF element's name="" (may be empty)
  std::string mesh_file;                     ///< path as written in the URDF; empty for a primitive
  Primitive primitive;                       ///< kNone for a <mesh>
  std::shared_ptr<const render::Mesh> mesh;  ///< loaded and scaled to metres
  Eigen::Isometry3d X_LinkVisual = Eigen::Isometry3d::Identity();
  render::Rgba colour{0.7f, 0.7f, 0.7f, 1.0f};
};

struct Link {
  std::string name;
  double mass_kg = 0;
  Eigen::Vector3d com_m = Eigen::Vector3d::Zero();         ///< centre of mass in the link frame
  Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero();  ///< principal moments at the COM
  std::vector<Visual> visuals;
  std::vector<Visual> collisions;
  int parent_joint = -1;  ///< -1 for the root (the static bed)
};

enum class JointType { kFixed, kPrismatic, kRevolute, kContinuous };

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d X_ParentJoint = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit, in the joint (= child) frame
  double lower = 0, upper = 0;                      ///< m | rad (not for continuous)
  double damping = 0;                               ///< N s/m | N m s/rad
  double friction = 0;                              ///< N | N m
};

/// The gains and limits one drive parameter set holds. A drive has up to eight (SERCOS S-0-0217
/// selects one each cycle, DriveSetpoint::parameter_set; C-axis manual 2.2: a main spindle with
/// rotary axis capability has one for spindle mode and one for rotary axis mode). SI after
/// loading (m or rad).
struct DriveParameterSet {
  /// Spindle behaviour in position mode: M19 orientation along the drive's own profile. A servo
  /// set follows the master's cyclically interpolated position through the Kv loop instead.
  bool spindle = false;
  double kv_per_s = 30;              ///< position loop gain
  double velocity_kp = 0;            ///< velocity loop P gain, N s/m | N m s/rad (load side)
  double velocity_ti_s = 0.01;       ///< velocity loop integral time
  double torque_limit = 0;           ///< N | N m (load side)
  double velocity_limit = 0;         ///< m/s | rad/s
  double acceleration_limit = 0;     ///< m/s^2 | rad/s^2 (spindle ramp, profiles)
  double in_position_window = 0;     ///< m | rad
  double standstill_window = 0;      ///< m/s | rad/s
  double following_error_limit = 0;  ///< m | rad
  double positioning_speed = 0;      ///< rad/s, spindle M19 orientation speed
};

/// A drive's controller, as a servo or spindle amplifier would be parameterised. Its own gains
/// and limits (the DriveParameterSet it derives from) are parameter set 0.
/// Gains and limits are stored in SI (m or rad) after loading.
struct DriveParams : DriveParameterSet {
  control::DriveInfo info;
  int motor_joint = -1;  ///< joint the motor torque acts on
  double ratio = 1;      ///< motor units per load unit (belt, gear reduction)
  /// `encoder: load`: the joint a load-side (external) encoder reads, for the position loop and
  /// the feedback position; the velocity loop stays on the motor. -1: the motor encoder
  /// (motor_joint / ratio).
  int load_joint = -1;
  double encoder_resolution = 0;  ///< m | rad, load side
  /// `modulo:` (rotary drives): the position is modulo this (rad), as a SERCOS drive with
  /// modulo scaling (S-0-0076, S-0-0103) reports it, and the position loop takes the shorter
  /// way to its command. 0: absolute. A C axis that reads the spindle's encoder needs it: in
  /// spindle mode the spindle turns thousands of degrees under it.
  double modulo = 0;
  /// The amplifier trips (kOverload) after this long at its torque limit, s (net: time below
  /// the limit counts back down).
  double overload_time_s = 1;
  /// `torque_threshold:` Mdx (SERCOS S-0-0126), N | N m load side: status kTorqueThreshold
  /// while |torque| >= it. 0: none, the bit stays clear.
  double torque_threshold = 0;
  /// `power_threshold:` Px (SERCOS S-0-0158), W: status kPowerThreshold while the mechanical
  /// power |torque x velocity| >= it. 0: none, the bit stays clear.
  double power_threshold_w = 0;
  /// `probe_inputs: {PIN4: .., PIN5: ..}`: the I/O inputs wired to the drive's probe inputs E4
  /// (probe 1) and E5 (probe 2) (fast-measurement manual 7.3; TASTWERKZEUGPAGE element 3 picks
  /// the pin). -1: not wired, the input reads 0.
  std::array<int, 2> probe_inputs = {-1, -1};
  /// Every set the drive has: [0] is the drive's own keys, [n] = YAML parameter_sets[n - 1]
  /// (set 0 with that entry's overrides).
  std::vector<DriveParameterSet> parameter_sets;
  // Step response spec the tests hold the drive to (machine YAML `spec:`).
  double spec_settle_time_s = 0;
  double spec_overshoot = 0;  ///< m | rad
};

struct GearCoupling {
  std::string name;
  int motor_joint = -1, load_joint = -1;
  double ratio = 1;  ///< motor turns per load turn
};

/// A dog clutch between a motor and the load it may drive through a gear (C-axis manual 4.4:
/// the C servo reaches the spindle through clutch K; valves QROTMODE/QSPMODE, switches
/// IROTMODE/ISPMODE).
struct DogClutch {
  std::string name;
  int motor_joint = -1, load_joint = -1;
  double ratio = 1;                     ///< motor turns per load turn when engaged
  int teeth = 1;                        ///< dog teeth; pitch = 2 pi / teeth on the load side
  double phase_tolerance_rad = 0;       ///< load-side tooth phase error that still meshes
  double max_relative_speed_rad_s = 0;  ///< load-side slip speed above which teeth ratchet
  double engage_time_s = 0;             ///< valve + stroke time
  double release_time_s = 0;
  int valve_engage = -1, valve_release = -1;      ///< I/O indices (outputs)
  int sensor_engaged = -1, sensor_released = -1;  ///< I/O indices (inputs)
};

/// A valve-driven device beside the clutches (tailstock quill, turret clamp, coolant pump, door,
/// probe switch-on). Its valve (monostable: spring or second coil returns it) moves it to its on
/// end in time_on and back to its off end in time_off; end switches report the two ends.
struct Actuator {
  std::string name;
  int valve = -1;                       ///< I/O index (output)
  int on_switch = -1, off_switch = -1;  ///< I/O indices (inputs), -1 when the device has none
  double time_on_s = 0, time_off_s = 0;
  /// A clamp: the drive's joint is held unless the device is fully on (released), with up to
  /// hold_torque (N | N m, load side) -- a drive that pushes against it lags and faults.
  int holds_drive = -1;
  double hold_torque = 0;
};

/// A cam switch on an axis: on while the drive's position is within `window` of a multiple of
/// `pitch` (turret in position at a station), machine units (mm | deg).
struct PositionSwitch {
  int input = -1;  ///< I/O index
  int drive = -1;
  double pitch = 0, window = 0;
};

/// A tool's cutting part (machine.yaml `cutting_parts:`, a URDF <collision> name): where it
/// passes through the workpiece while the spindle turns, it cuts (sim/collision/turned_stock).
struct CuttingPart {
  int link = -1;
  int collision = -1;  ///< index into links[link].collisions
};

struct MachineModel {
  std::string name;
  std::string yaml_path, urdf_path;
  std::vector<Link> links;    ///< links[0] is the root
  std::vector<Joint> joints;  ///< topological order: a joint's parent link comes first
  std::vector<DriveParams> drives;
  std::vector<control::IoInfo> io;
  std::vector<GearCoupling> gears;
  std::vector<DogClutch> clutches;
  std::vector<Actuator> actuators;
  std::vector<PositionSwitch> position_switches;
  std::vector<CuttingPart> cutting_parts;
  std::vector<NamedCamera> cameras;
  NcMachineData nc;  ///< machine.yaml `nc:`; not present for a machine without NC
  /// machine.yaml `probe:`: the measuring styluses (TASTWERKZEUGPAGE), up to four.
  std::vector<ProbeStylus> probes;

  std::vector<control::DriveInfo> DriveInfos() const;
  int LinkIndex(const std::string& name) const;
  int JointIndex(const std::string& name) const;
  int DriveIndex(const std::string& name) const;
};

/// Load machine.yaml and the URDF it names. Throws ModelError naming the file and the YAML
/// path (or URDF element) of the fault.
MachineModel LoadMachineModel(const std::string& machine_yaml_path);

/// World poses of every link for the given joint positions (SI, one per joint).
std::vector<Eigen::Isometry3d> LinkPoses(const MachineModel& model, const std::vector<double>& q);

/// The links whose poses those of `links` are built from: themselves and every link between
/// them and the root (marked by link index).
std::vector<bool> LinkChains(const MachineModel& model, const std::vector<int>& links);

/// LinkPoses for the links `needed` marks (LinkChains), into X_W (one per link, identities when
/// it has another size; the others are left as they are): the same bits as LinkPoses gives them,
/// for a caller that needs a few links every tick.
void LinkPoses(const MachineModel& model, const std::vector<double>& q,
               const std::vector<bool>& needed, std::vector<Eigen::Isometry3d>& X_W);

}  // namespace vmt::sim
