// Featherstone (btMultiBody) vs constraint-based rigid bodies for the lathe's axis chain: the
// numbers behind the choice documented in sim/physics/physics_backend.hpp.
//
// Chain (models/lathe-c1/machine.urdf; world = bed frame, y up, gravity -y):
//   bed (fixed) -> z_carriage (prismatic z) -> x_slide (prismatic x) -> turret (revolute z)
//   bed -> spindle (revolute z)
// Both variants are built from the same constants, driven by the same servo at the 250 us drive
// tick for 5 s, and measured the same way. Argument = spindle speed in rpm. Counters:
//   us_per_step            wall time per tick: servo, step, read-back and the (cheap) measurements;
//                          world construction excluded (the Time column includes it)
//   max_offaxis_m          max distance of the x_slide frame origin from (x, 0, z) built from the
//                          variant's own joint readings, i.e. the joints' drift off their axes
//   max_tilt_rad           max angle between the turret axis and world z
//   max_tracking_error_m   max |command - reading| of Z and X
//   spindle_rpm_reached    spindle speed from the angle reading over the last second
//   spindle_rpm_velocity   spindle speed from the velocity reading at the end
//   spindle_angle_error_rad  |angle reading - integral of the velocity reading| at the end
// Self-contained on purpose: it must not depend on the backend it evaluates.

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

namespace {

constexpr double kDt = 250e-6;
constexpr int kSteps = 20000;  // 5 s
constexpr double kPi = 3.14159265358979323846;

// URDF inertials: link frame = joint frame at q = 0, inertia diagonal about the COM.
struct LinkDef {
  double mass;
  btVector3 com;
  btVector3 inertia;
};
const LinkDef kCarriage{120, {0.35, -0.28, 0.21}, {1.588, 3.208, 1.908}};
const LinkDef kSlide{80, {0.338113857, -0.06949077, 0.213502698}, {1.24992, 1.51389, 1.67455}};
const LinkDef kTurret{60, {0, 0, 0}, {0.343871, 0.343871, 0.6}};
const LinkDef kSpindle{45, {0, 0, 0.052884179}, {0.17191, 0.17191, 0.25}};
const btVector3 kTurretPivot(0.18, 0, 0.06);  // turret joint origin in the x_slide frame

enum Joint { kZ, kX, kT, kS, kJoints };
using Vec = std::array<double, kJoints>;

// Commanded trajectory: Z 300 + 100 sin(2 pi t) mm, X 100 + 40 sin(3 pi t) mm, turret
// 90 sin(2 pi t) deg; spindle velocity ramps to speed in 0.5 s.
struct Command {
  Vec q{}, v{}, a{};
};
Command Trajectory(double t, double spindle_rad_s) {
  Command c;
  const auto sine = [&](Joint j, double mean, double amp, double w) {
    c.q[j] = mean + amp * std::sin(w * t);
    c.v[j] = amp * w * std::cos(w * t);
    c.a[j] = -amp * w * w * std::sin(w * t);
  };
  sine(kZ, 0.300, 0.100, 2 * kPi * 1.0);
  sine(kX, 0.100, 0.040, 2 * kPi * 1.5);
  sine(kT, 0.0, kPi / 2, 2 * kPi * 1.0);
  constexpr double kRampS = 0.5;
  c.v[kS] = spindle_rad_s * std::min(t / kRampS, 1.0);
  c.a[kS] = t < kRampS ? spindle_rad_s / kRampS : 0.0;
  return c;
}

// Cascaded P position / P velocity loop with velocity and acceleration feedforward, scaled by the
// load each drive moves so that all loops have the same bandwidth.
const Vec kLoad{kCarriage.mass + kSlide.mass + kTurret.mass, kSlide.mass + kTurret.mass,
                kTurret.inertia.z(), kSpindle.inertia.z()};
constexpr double kVelBandwidth = 500;  // rad/s
constexpr double kPosGain = 40;        // 1/s
Vec Servo(const Command& c, const Vec& q, const Vec& qd) {
  Vec f{};
  for (int j = 0; j < kJoints; ++j) {
    const double v_ref = c.v[j] + (j == kS ? 0.0 : kPosGain * (c.q[j] - q[j]));
    f[j] = kLoad[j] * (c.a[j] + kVelBandwidth * (v_ref - qd[j]));
  }
  return f;
}

double Angle(const btVector3& a, const btVector3& b) {
  return std::atan2(a.cross(b).length(), a.dot(b));
}

// ---- Variant 1: one btMultiBody, joint coordinates are the state. -------------------------------
class Featherstone {
 public:
  Featherstone(const Vec& q0, const Vec& qd0) {
    world_.setGravity(btVector3(0, -9.81, 0));
    // Fixed base = bed frame at the world origin (its inertia is irrelevant when fixed).
    mb_ = std::make_unique<btMultiBody>(kJoints, 0.0, btVector3(0, 0, 0), true, false);
    const btQuaternion id = btQuaternion::getIdentity();
    const btVector3 o(0, 0, 0);
    // Offsets: parent COM -> joint origin, joint origin -> child COM.
    mb_->setupPrismatic(kZ, kCarriage.mass, kCarriage.inertia, -1, id, {0, 0, 1}, o, kCarriage.com,
                        true);
    mb_->setupPrismatic(kX, kSlide.mass, kSlide.inertia, kZ, id, {1, 0, 0}, -kCarriage.com,
                        kSlide.com, true);
    mb_->setupRevolute(kT, kTurret.mass, kTurret.inertia, kX, id, {0, 0, 1},
                       kTurretPivot - kSlide.com, kTurret.com, true);
    mb_->setupRevolute(kS, kSpindle.mass, kSpindle.inertia, -1, id, {0, 0, 1}, o, kSpindle.com,
                       true);
    mb_->finalizeMultiDof();
    // Game defaults would damp the axes and cap the spindle at 100 rad/s.
    mb_->setLinearDamping(0);
    mb_->setAngularDamping(0);
    mb_->setMaxCoordinateVelocity(1e5);
    mb_->setCanSleep(false);
    for (int j = 0; j < kJoints; ++j) {
      mb_->setJointPos(j, q0[j]);
      mb_->setJointVel(j, qd0[j]);
    }
    world_.addMultiBody(mb_.get());
  }
  ~Featherstone() { world_.removeMultiBody(mb_.get()); }

  void Read(Vec& q, Vec& qd) const {
    for (int j = 0; j < kJoints; ++j) q[j] = mb_->getJointPos(j), qd[j] = mb_->getJointVel(j);
  }
  void Drive(const Vec& f) {
    for (int j = 0; j < kJoints; ++j) mb_->addJointTorque(j, f[j]);
  }
  void Step() { world_.stepSimulation(kDt, 0, kDt); }
  // Link frames from the articulated state (Bullet's link frame is at the COM).
  btVector3 SlideOrigin() const { return mb_->localPosToWorld(kX, -kSlide.com); }
  btVector3 TurretAxis() const { return mb_->localDirToWorld(kT, btVector3(0, 0, 1)); }

 private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  btMultiBodyConstraintSolver solver_;
  btMultiBodyDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &config_};
  std::unique_ptr<btMultiBody> mb_;
};

// ---- Variant 2: a btRigidBody per link, joints as constraints. ----------------------------------
class Constraints {
 public:
  Constraints(const Vec& q0, const Vec& qd0) {
    world_.setGravity(btVector3(0, -9.81, 0));  // before adding bodies: they copy it
    const btVector3 z(0, 0, 1);
    bed_ = Body(LinkDef{0, {0, 0, 0}, {0, 0, 0}}, btTransform::getIdentity());
    // Bodies sit at their COM (principal axes = link axes, the inertias are diagonal).
    carriage_ = Body(kCarriage, Frame({0, 0, q0[kZ]}, 0));
    slide_ = Body(kSlide, Frame({q0[kX], 0, q0[kZ]}, 0));
    turret_ = Body(kTurret, Frame(btVector3(q0[kX], 0, q0[kZ]) + kTurretPivot, q0[kT]));
    spindle_ = Body(kSpindle, Frame({0, 0, 0}, q0[kS]));
    carriage_->setLinearVelocity({0, 0, qd0[kZ]});
    slide_->setLinearVelocity({qd0[kX], 0, qd0[kZ]});
    turret_->setLinearVelocity({qd0[kX], 0, qd0[kZ]});  // turret COM is on its axis
    turret_->setAngularVelocity(z * qd0[kT]);
    spindle_->setAngularVelocity(z * qd0[kS]);

    // Slider axis = constraint frame x. Lower > upper frees the travel; angular limits lock.
    const btMatrix3x3 x_to_z(btQuaternion(btVector3(0, 1, 0), -kPi / 2));
    z_ = Slider(*bed_, *carriage_, btTransform(x_to_z), btTransform(x_to_z, -kCarriage.com));
    x_ = Slider(*carriage_, *slide_, btTransform(btMatrix3x3::getIdentity(), -kCarriage.com),
                btTransform(btMatrix3x3::getIdentity(), -kSlide.com));
    turret_hinge_ = Hinge(*slide_, *turret_, kTurretPivot - kSlide.com, -kTurret.com);
    spindle_hinge_ = Hinge(*bed_, *spindle_, {0, 0, 0}, -kSpindle.com);
    turret_angle_.Reset(turret_hinge_->getHingeAngle());
    spindle_angle_.Reset(spindle_hinge_->getHingeAngle());
  }
  ~Constraints() {
    for (auto* c : {z_.get(), x_.get()}) world_.removeConstraint(c);
    for (auto* c : {turret_hinge_.get(), spindle_hinge_.get()}) world_.removeConstraint(c);
    for (auto* b : {bed_.get(), carriage_.get(), slide_.get(), turret_.get(), spindle_.get()})
      world_.removeRigidBody(b);
  }

  void Read(Vec& q, Vec& qd) {
    // getLinearPos() is what the solver saw, i.e. the pre-step pose: a one-tick-old encoder. It is
    // refreshed by testLinLimits() from calculateTransforms()' result, not by the latter alone.
    const auto slider_pos = [](btSliderConstraint& s) {
      s.calculateTransforms(s.getRigidBodyA().getCenterOfMassTransform(),
                            s.getRigidBodyB().getCenterOfMassTransform());
      s.testLinLimits();
      return s.getLinearPos();
    };
    q[kZ] = slider_pos(*z_);
    q[kX] = slider_pos(*x_);
    q[kT] = turret_angle_.Update(turret_hinge_->getHingeAngle());
    q[kS] = spindle_angle_.Update(spindle_hinge_->getHingeAngle());
    // Velocities relative to the parent, along the parent's joint axis.
    qd[kZ] = carriage_->getLinearVelocity().z();
    qd[kX] = (slide_->getLinearVelocity() - carriage_->getLinearVelocity())
                 .dot(carriage_->getWorldTransform().getBasis().getColumn(0));
    qd[kT] = (turret_->getAngularVelocity() - slide_->getAngularVelocity())
                 .dot(slide_->getWorldTransform().getBasis().getColumn(2));
    qd[kS] = spindle_->getAngularVelocity().z();
  }
  void Drive(const Vec& f) {
    // Equal and opposite on child and parent, as a drive mounted on the parent would act.
    const auto push = [](btRigidBody& child, btRigidBody& parent, const btVector3& force) {
      child.applyCentralForce(force);
      parent.applyCentralForce(-force);
    };
    const auto twist = [](btRigidBody& child, btRigidBody& parent, const btVector3& torque) {
      child.applyTorque(torque);
      parent.applyTorque(-torque);
    };
    const btMatrix3x3& carriage = carriage_->getWorldTransform().getBasis();
    push(*carriage_, *bed_, btVector3(0, 0, f[kZ]));
    push(*slide_, *carriage_, carriage.getColumn(0) * f[kX]);
    twist(*turret_, *slide_, slide_->getWorldTransform().getBasis().getColumn(2) * f[kT]);
    twist(*spindle_, *bed_, btVector3(0, 0, f[kS]));
  }
  void Step() { world_.stepSimulation(kDt, 0, kDt); }
  btVector3 SlideOrigin() const { return slide_->getWorldTransform() * -kSlide.com; }
  btVector3 TurretAxis() const { return turret_->getWorldTransform().getBasis().getColumn(2); }

 private:
  // getHingeAngle() is in [-pi, pi]: accumulate the wrapped increments (valid below pi/step).
  struct Unwrapper {
    double last = 0, total = 0;
    void Reset(double raw) { last = total = raw; }
    double Update(double raw) {
      total += std::remainder(raw - last, 2 * kPi);
      last = raw;
      return total;
    }
  };
  static btTransform Frame(const btVector3& joint_origin, double angle_about_z) {
    return btTransform(btQuaternion(btVector3(0, 0, 1), angle_about_z), joint_origin);
  }
  std::unique_ptr<btRigidBody> Body(const LinkDef& l, const btTransform& link_frame) {
    btRigidBody::btRigidBodyConstructionInfo info(l.mass, nullptr, &marker_shape_, l.inertia);
    info.m_startWorldTransform = link_frame * btTransform(btMatrix3x3::getIdentity(), l.com);
    auto b = std::make_unique<btRigidBody>(info);
    b->setDamping(0, 0);
    b->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(b.get(), 0, 0);  // group/mask 0: takes part in no collision at all
    return b;
  }
  std::unique_ptr<btSliderConstraint> Slider(btRigidBody& a, btRigidBody& b,
                                             const btTransform& in_a, const btTransform& in_b) {
    auto s = std::make_unique<btSliderConstraint>(a, b, in_a, in_b, true);
    s->setLowerLinLimit(1), s->setUpperLinLimit(-1);
    s->setLowerAngLimit(0), s->setUpperAngLimit(0);
    world_.addConstraint(s.get(), true);
    return s;
  }
  // Hinge axis = z of both frames; with the frames aligned to the link frames, the hinge angle
  // is the joint angle.
  std::unique_ptr<btHingeConstraint> Hinge(btRigidBody& a, btRigidBody& b, const btVector3& in_a,
                                           const btVector3& in_b) {
    const btMatrix3x3 id = btMatrix3x3::getIdentity();
    auto h = std::make_unique<btHingeConstraint>(a, b, btTransform(id, in_a), btTransform(id, in_b),
                                                 true);
    world_.addConstraint(h.get(), true);
    return h;
  }

  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &config_};
  btSphereShape marker_shape_{1e-3};  // the broadphase needs a shape; it collides with nothing
  std::unique_ptr<btRigidBody> bed_, carriage_, slide_, turret_, spindle_;
  std::unique_ptr<btSliderConstraint> z_, x_;
  std::unique_ptr<btHingeConstraint> turret_hinge_, spindle_hinge_;
  Unwrapper turret_angle_, spindle_angle_;
};

// ---- The run: same drive, same measurements for both. ------------------------------------------
struct Metrics {
  double us_per_step = 0, max_offaxis = 0, max_tilt = 0, max_tracking = 0;
  double rpm_reached = 0, rpm_velocity = 0, angle_error = 0;
};

template <class Chain>
Metrics Run(double spindle_rpm) {
  const double spindle_rad_s = spindle_rpm * 2 * kPi / 60;
  const Command c0 = Trajectory(0, spindle_rad_s);
  Chain chain(c0.q, c0.v);  // start on the trajectory: the errors are tracking, not start-up
  Metrics m;
  Vec q{}, qd{};
  double integral = 0, angle_at_4s = 0;  // spindle angle from integrating its velocity reading
  const auto start = std::chrono::steady_clock::now();
  chain.Read(q, qd);
  for (int i = 0; i < kSteps; ++i) {
    chain.Drive(Servo(Trajectory(i * kDt, spindle_rad_s), q, qd));
    chain.Step();
    chain.Read(q, qd);  // feeds both the measurements at (i + 1) dt and the next tick's servo
    const Command c = Trajectory((i + 1) * kDt, spindle_rad_s);
    // Bullet integrates positions with the post-step velocity (semi-implicit Euler).
    integral += qd[kS] * kDt;
    if (i + 1 == kSteps - static_cast<int>(1.0 / kDt)) angle_at_4s = q[kS];
    const btVector3 ideal(q[kX], 0, q[kZ]);
    m.max_offaxis = std::max(m.max_offaxis, (chain.SlideOrigin() - ideal).length());
    m.max_tilt = std::max(m.max_tilt, Angle(chain.TurretAxis(), btVector3(0, 0, 1)));
    m.max_tracking =
        std::max({m.max_tracking, std::abs(c.q[kZ] - q[kZ]), std::abs(c.q[kX] - q[kX])});
  }
  const std::chrono::duration<double, std::micro> elapsed =
      std::chrono::steady_clock::now() - start;
  m.us_per_step = elapsed.count() / kSteps;
  m.rpm_reached = (q[kS] - angle_at_4s) / 1.0 * 60 / (2 * kPi);
  m.rpm_velocity = qd[kS] * 60 / (2 * kPi);
  m.angle_error = std::abs(q[kS] - integral);
  return m;
}

template <class Chain>
void BM_AxisChain(benchmark::State& state) {
  Metrics m;
  double us = 0;
  for (auto _ : state) {
    m = Run<Chain>(static_cast<double>(state.range(0)));
    us += m.us_per_step;
  }
  state.SetItemsProcessed(state.iterations() * kSteps);
  state.counters["us_per_step"] = us / static_cast<double>(state.iterations());
  state.counters["max_offaxis_m"] = m.max_offaxis;
  state.counters["max_tilt_rad"] = m.max_tilt;
  state.counters["max_tracking_error_m"] = m.max_tracking;
  state.counters["spindle_rpm_reached"] = m.rpm_reached;
  state.counters["spindle_rpm_velocity"] = m.rpm_velocity;
  state.counters["spindle_angle_error_rad"] = m.angle_error;
}

}  // namespace

// 3000 rpm: the machine's speed. 12000: 4x headroom. 40000: past btRigidBody's rotation clamp
// (btTransformUtil::integrateTransform, pi/4 per step = 30000 rpm at 250 us). The clamp shortens
// the integrated rotation while the body keeps its angular velocity, so the angle falls behind it.
BENCHMARK_TEMPLATE(BM_AxisChain, Featherstone)
    ->Arg(3000)
    ->Arg(12000)
    ->Arg(40000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_AxisChain, Constraints)
    ->Arg(3000)
    ->Arg(12000)
    ->Arg(40000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
