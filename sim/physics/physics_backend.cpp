#include "sim/physics/physics_backend.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>

namespace vmt::sim {
namespace {

// Gears are stiff: their position error is corrected within a few ticks.
constexpr double kGearErp = 0.2;
constexpr double kGearMaxImpulse = 1e9;
// A clamp pulls a joint that crept under its hold torque back to where it clamped.
constexpr double kClampPositionGain = 0.2;
// Coulomb friction is smoothed over this speed so that standstill does not chatter.
constexpr double kFrictionSmoothing = 1e-4;

btVector3 Bt(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

struct PhysicsBackend::World {
  btDefaultCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &collision_config};
  std::unique_ptr<btMultiBody> body;
  btSphereShape marker_shape{1e-3};
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btMultiBodyGearConstraint>> gears;
  std::vector<std::unique_ptr<btMultiBodyGearConstraint>> clutch_gears;  ///< null when open
  std::vector<std::unique_ptr<btMultiBodyJointMotor>> clamps;  ///< per actuator, null when free

  std::unique_ptr<btMultiBodyGearConstraint> Gear(int motor_joint, int load_joint, double ratio,
                                                  double offset) {
    // Bullet enforces q_A + r q_B = target: with A = motor and r = -ratio this is
    // q_motor = ratio * (q_load - offset).
    auto g = std::make_unique<btMultiBodyGearConstraint>(
        body.get(), motor_joint, body.get(), load_joint, btVector3(0, 0, 0), btVector3(0, 0, 0),
        btMatrix3x3::getIdentity(), btMatrix3x3::getIdentity());
    g->setGearRatio(-ratio);
    g->setErp(kGearErp);
    g->setRelativePositionTarget(-ratio * offset);
    g->setMaxAppliedImpulse(kGearMaxImpulse);
    world.addMultiBodyConstraint(g.get());
    return g;
  }
};

PhysicsBackend::PhysicsBackend(const MachineModel& model, const InitialState& init)
    : MachineBackend(model, init), world_(std::make_unique<World>()) {
  world_->clutch_gears.resize(model.clutches.size());
  world_->clamps.resize(model.actuators.size());
  world_->world.setGravity(btVector3(0, -9.81, 0));

  // Link i of the multibody is joint i of the model (joints are in topological order and
  // joint i's child is model link i + 1).
  const int n = static_cast<int>(model.joints.size());
  world_->body = std::make_unique<btMultiBody>(n, 0.0, btVector3(0, 0, 0), true, false);
  btMultiBody& mb = *world_->body;
  for (int j = 0; j < n; ++j) {
    const Joint& joint = model.joints[j];
    const Link& child = model.links[joint.child_link];
    const Link& parent = model.links[joint.parent_link];
    // Featherstone needs mass on every moving link; massless URDF links get a token one.
    const double mass = std::max(child.mass_kg, 1e-3);
    const btVector3 inertia = Bt(child.inertia_kgm2.cwiseMax(1e-6));
    const Eigen::Quaterniond q_ThisParent(joint.X_ParentJoint.linear().transpose());
    const btQuaternion rot_parent_to_this(q_ThisParent.x(), q_ThisParent.y(), q_ThisParent.z(),
                                          q_ThisParent.w());
    // The fixed base sits at the world origin with its frame there, whatever the bed's COM.
    const Eigen::Vector3d parent_com =
        joint.parent_link == 0 ? Eigen::Vector3d::Zero() : parent.com_m;
    const btVector3 parent_com_to_pivot = Bt(joint.X_ParentJoint.translation() - parent_com);
    const btVector3 pivot_to_com = Bt(child.com_m);
    const int parent_index = joint.parent_link - 1;
    switch (joint.type) {
      case JointType::kFixed:
        mb.setupFixed(j, mass, inertia, parent_index, rot_parent_to_this, parent_com_to_pivot,
                      pivot_to_com);
        break;
      case JointType::kPrismatic:
        mb.setupPrismatic(j, mass, inertia, parent_index, rot_parent_to_this, Bt(joint.axis),
                          parent_com_to_pivot, pivot_to_com, true);
        break;
      case JointType::kRevolute:
      case JointType::kContinuous:
        mb.setupRevolute(j, mass, inertia, parent_index, rot_parent_to_this, Bt(joint.axis),
                         parent_com_to_pivot, pivot_to_com, true);
        break;
    }
  }
  mb.finalizeMultiDof();
  // Bullet's defaults suit games: damping would brake a coasting spindle, and the coordinate
  // velocity clamp (100 rad/s, 955 rpm) would cap it.
  mb.setLinearDamping(0);
  mb.setAngularDamping(0);
  mb.setMaxCoordinateVelocity(1e5);
  mb.setCanSleep(false);
  mb.setHasSelfCollision(false);

  const std::vector<double> q0 = InitialJointPositions(model, init);
  for (int j = 0; j < n; ++j)
    if (model.joints[j].type != JointType::kFixed) mb.setJointPos(j, q0[j]);
  world_->world.addMultiBody(&mb);
  // Bullet solves multibody constraints per simulation island, and only objects with colliders
  // belong to one (its no-island path drops multibody constraints). The links get colliders that
  // collide with nothing: geometry questions go to FCL, contacts come with the probe issue.
  for (int j = 0; j < n; ++j) {
    auto col = std::make_unique<btMultiBodyLinkCollider>(&mb, j);
    col->setCollisionShape(&world_->marker_shape);
    col->setActivationState(DISABLE_DEACTIVATION);
    world_->world.addCollisionObject(col.get(), 0, 0);
    mb.getLink(j).m_collider = col.get();
    world_->colliders.push_back(std::move(col));
  }

  for (const GearCoupling& g : model.gears)
    world_->gears.push_back(world_->Gear(g.motor_joint, g.load_joint, g.ratio, 0));
  for (size_t k = 0; k < model.clutches.size(); ++k)
    if (clutches_[k].state == ClutchState::kEngaged) Couple(static_cast<int>(k));

  for (size_t k = 0; k < model.actuators.size(); ++k)
    if (actuators_[k].Holds(model.actuators[k])) Clamp(static_cast<int>(k), true);

  torques_.assign(model.drives.size(), 0.0);
  UpdateFeedback(torques_);
  StartProbes([&mb](int j) { return mb.getJointPos(j); });
}

PhysicsBackend::~PhysicsBackend() {
  for (auto& c : world_->clamps)
    if (c) world_->world.removeMultiBodyConstraint(c.get());
  for (auto& g : world_->clutch_gears)
    if (g) world_->world.removeMultiBodyConstraint(g.get());
  for (auto& g : world_->gears) world_->world.removeMultiBodyConstraint(g.get());
  for (auto& col : world_->colliders) world_->world.removeCollisionObject(col.get());
  world_->world.removeMultiBody(world_->body.get());
}

std::vector<double> PhysicsBackend::JointPositions() const {
  std::vector<double> q(model_->joints.size(), 0.0);
  for (size_t j = 0; j < q.size(); ++j)
    if (model_->joints[j].type != JointType::kFixed)
      q[j] = world_->body->getJointPos(static_cast<int>(j));
  return q;
}

std::vector<double> PhysicsBackend::JointVelocities() const {
  std::vector<double> qd(model_->joints.size(), 0.0);
  for (size_t j = 0; j < qd.size(); ++j)
    if (model_->joints[j].type != JointType::kFixed)
      qd[j] = world_->body->getJointVel(static_cast<int>(j));
  return qd;
}

void PhysicsBackend::Couple(int k) {
  const DogClutch& c = model_->clutches[k];
  btMultiBody& mb = *world_->body;
  const double offset =
      DogClutchLogic::MeshOffset(c, mb.getJointPos(c.motor_joint), mb.getJointPos(c.load_joint));
  world_->clutch_gears[k] = world_->Gear(c.motor_joint, c.load_joint, c.ratio, offset);
}

void PhysicsBackend::Uncouple(int k) {
  if (!world_->clutch_gears[k]) return;
  world_->world.removeMultiBodyConstraint(world_->clutch_gears[k].get());
  world_->clutch_gears[k].reset();
}

void PhysicsBackend::Clamp(int k, bool hold) {
  std::unique_ptr<btMultiBodyJointMotor>& c = world_->clamps[k];
  if (!hold) {
    if (c) world_->world.removeMultiBodyConstraint(c.get());
    c.reset();
    return;
  }
  if (c) return;
  const Actuator& a = model_->actuators[k];
  const DriveParams& p = model_->drives[a.holds_drive];
  btMultiBody& mb = *world_->body;
  // The hold torque is load side; the joint is the drive's motor joint.
  c = std::make_unique<btMultiBodyJointMotor>(&mb, p.motor_joint, 0.0,
                                              a.hold_torque / p.ratio * kDriveTickS);
  c->setPositionTarget(mb.getJointPos(p.motor_joint), kClampPositionGain);
  world_->world.addMultiBodyConstraint(c.get());
}

void PhysicsBackend::Step() {
  const double dt = kDriveTickS;
  btMultiBody& mb = *world_->body;

  std::vector<double>& torques = torques_;  // member: no allocation per tick
  for (size_t d = 0; d < controllers_.size(); ++d) {
    const DriveParams& p = model_->drives[d];
    // Position loop on its encoder (possibly load side), velocity loop on the motor.
    const double pos = EncoderPosition(p, [&mb](int j) { return mb.getJointPos(j); });
    const double vel = LoadSide(p, mb.getJointVel(p.motor_joint));
    DriveController& ctrl = controllers_[d];
    const double v_ref = ctrl.VelocityReference(ToSi(p, mdt_.setpoints[d]), pos, vel, dt);
    torques[d] = ctrl.Torque(v_ref, vel, dt);
    mb.addJointTorque(p.motor_joint, torques[d] / p.ratio);
  }
  for (size_t j = 0; j < model_->joints.size(); ++j) {
    const Joint& joint = model_->joints[j];
    if (joint.type == JointType::kFixed || (joint.damping == 0 && joint.friction == 0)) continue;
    const double qd = mb.getJointVel(static_cast<int>(j));
    mb.addJointTorque(static_cast<int>(j),
                      -joint.damping * qd - joint.friction * std::tanh(qd / kFrictionSmoothing));
  }

  for (size_t k = 0; k < actuators_.size(); ++k) {
    const Actuator& a = model_->actuators[k];
    actuators_[k].Step(a, mdt_.outputs[a.valve], dt);
    if (a.holds_drive >= 0) Clamp(static_cast<int>(k), actuators_[k].Holds(a));
  }

  // The styluses step between the links' poses before and after the physics moved them.
  if (styluses_.any()) q_before_ = JointPositions();
  world_->world.stepSimulation(dt, 0, dt);

  for (size_t k = 0; k < clutches_.size(); ++k) {
    const DogClutch& c = model_->clutches[k];
    const double qm = mb.getJointPos(c.motor_joint), ql = mb.getJointPos(c.load_joint);
    const double slip = mb.getJointVel(c.load_joint) - mb.getJointVel(c.motor_joint) / c.ratio;
    const bool was_engaged = clutches_[k].state == ClutchState::kEngaged;
    clutches_[k].Step(c, mdt_.outputs[c.valve_engage], mdt_.outputs[c.valve_release],
                      DogClutchLogic::PhaseError(c, qm, ql), slip, dt);
    const bool engaged = clutches_[k].state == ClutchState::kEngaged;
    if (engaged && !was_engaged) Couple(static_cast<int>(k));
    if (!engaged && was_engaged) Uncouple(static_cast<int>(k));
  }
  // Before the drives sample: a contact within this tick latches where it was.
  if (styluses_.any()) styluses_.Step(q_before_, JointPositions(), at_.inputs, time_s(), probes_);
  ++ticks_;
  UpdateFeedback(torques);
  SampleProbes([&mb](int j) { return mb.getJointPos(j); });
}

void PhysicsBackend::UpdateFeedback(const std::vector<double>& torques) {
  const btMultiBody& mb = *world_->body;
  for (size_t d = 0; d < controllers_.size(); ++d) {
    const DriveParams& p = model_->drives[d];
    controllers_[d].Feedback(EncoderPosition(p, [&mb](int j) { return mb.getJointPos(j); }),
                             LoadSide(p, mb.getJointVel(p.motor_joint)), torques[d],
                             at_.feedback[d]);
  }
  ReadInputs();
}

}  // namespace vmt::sim
