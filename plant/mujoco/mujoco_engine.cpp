#include "plant/mujoco/mujoco_engine.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "plant/mujoco/mujoco_model.hpp"
#include "util/error.hpp"

namespace lagrange::plant {

namespace {

void countOnly(const char*) {}  // warnings are read from mjData::warning
void fatal(const char* message) {
  // MuJoCo's C code cannot unwind a C++ exception: report and end the process
  // (exit 1, a failed run), saying whose fault it is.
  std::fprintf(stderr,
               "plant: MuJoCo stopped with an error of its own (the engine's, not the control loop's): %s\n",
               message);
  std::_Exit(1);
}

void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = countOnly;
    mju_user_error = fatal;
  });
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

std::unique_ptr<mjModel, ModelDeleter> compile(const std::string& xml) {
  // MuJoCo 2.2's compiler swaps the global error handlers while it runs:
  // one compile at a time in a process.
  static std::mutex compiling;
  const std::lock_guard<std::mutex> lock(compiling);
  // From memory: a virtual file holds the document (mjVFS is 2 MB: on the heap).
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* name = "lagrange_arm.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw std::invalid_argument("plant.engine mujoco: cannot hold the model in memory");
  const int index = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), error, sizeof error);
  if (!m)
    throw std::invalid_argument(std::string("plant.engine mujoco: MuJoCo refuses the arm's model: ") + error);
  return std::unique_ptr<mjModel, ModelDeleter>(m);
}

class MujocoEngine final : public PhysicsEngine {
 public:
  explicit MujocoEngine(const EngineSetup& setup)
      : dof_(setup.arm.dof), flexible_(setup.flexible), joints_(setup.joints) {
    if (!setup.arm.bodies)
      throw std::invalid_argument(
          "plant.engine: mujoco cannot simulate this arm: its robot kind describes it for ODE only (no "
          "bodies; plant/arm_world.hpp); expected plant.engine: ode");
    installHandlers();
    const ArmBodies& arm = *setup.arm.bodies;
    if (dof_ < 1 || static_cast<int>(arm.bodies.size()) != dof_)
      throw std::invalid_argument("plant.engine mujoco: the robot kind gives " +
                                  std::to_string(arm.bodies.size()) + " bodies for " + std::to_string(dof_) +
                                  " joints; expected one body per joint");
    model_ = compile(mujocoModelXml(arm, setup));
    data_.reset(mj_makeData(model_.get()));
    probe_.reset(mj_makeData(model_.get()));
    if (!data_ || !probe_) throw RuntimeFault("plant.engine mujoco: no memory for the arm's state");
    gravity_ = arm.gravity;
    for (int i = 0; i < dof_; ++i) {
      d()->qpos[qpos(i)] = setup.initial.q(i);
      d()->qvel[dofAt(i)] = setup.initial.qdot(i);
      if (flexible_) {
        d()->qpos[qpos(dof_ + i)] = setup.initial.motor_q(i);
        d()->qvel[dofAt(dof_ + i)] = setup.initial.motor_qdot(i);
      }
    }
    mj_forward(model_.get(), d());
  }

  void step(const Eigen::VectorXd& tau) override {
    // Rigid: the joints' torques. Flexible: the rotors'; the tendons carry the springs.
    const int offset = flexible_ ? dof_ : 0;
    for (int i = 0; i < dof_; ++i) d()->qfrc_applied[dofAt(offset + i)] = tau(i);
    mj_step(model_.get(), d());
    mj_kinematics(model_.get(), d());  // the axes of the state reached, for fastestBodyRate
    addDissipation();
  }

  PlantState state() const override {
    PlantState s;
    s.q.resize(dof_);
    s.qdot.resize(dof_);
    for (int i = 0; i < dof_; ++i) {
      s.q(i) = d()->qpos[qpos(i)];
      s.qdot(i) = d()->qvel[dofAt(i)];
    }
    if (flexible_) {
      s.motor_q.resize(dof_);
      s.motor_qdot.resize(dof_);
      for (int i = 0; i < dof_; ++i) {
        s.motor_q(i) = d()->qpos[qpos(dof_ + i)];
        s.motor_qdot(i) = d()->qvel[dofAt(dof_ + i)];
      }
    }
    return s;
  }

  PlantEnergy energy() const override {
    // On a copy of the state, so that reading it never changes what the next step does.
    mjData* p = probe_.get();
    std::copy(d()->qpos, d()->qpos + model_->nq, p->qpos);
    std::copy(d()->qvel, d()->qvel + model_->nv, p->qvel);
    mj_forward(model_.get(), p);
    PlantEnergy e;
    e.kinetic = p->energy[1];  // links and rotors: 1/2 qdot' M qdot
    // The links' heights only (the rotors' hinges hold them), as ODE counts them.
    for (int b = 1; b <= dof_; ++b)
      e.potential -= model_->body_mass[b] *
                     gravity_.dot(Eigen::Vector3d(p->xipos[3 * b], p->xipos[3 * b + 1], p->xipos[3 * b + 2]));
    if (flexible_)
      for (int i = 0; i < dof_; ++i) {
        const double twist = d()->qpos[qpos(dof_ + i)] - d()->qpos[qpos(i)];
        e.potential += 0.5 * flexible_->stiffness(i) * twist * twist;
      }
    return e;
  }

  double dissipated() const override { return dissipated_; }

  double fastestBodyRate() const override {
    // A link turns at the sum of its joints' axes times their rates, base to tip.
    double worst = 0.0;
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();
    for (int i = 0; i < dof_; ++i) {
      const int j = i;  // joint i moves body i + 1
      const mjtNum* a = d()->xaxis + 3 * j;
      omega += Eigen::Vector3d(a[0], a[1], a[2]) * d()->qvel[dofAt(i)];
      worst = std::max(worst, omega.norm());
    }
    if (flexible_)
      for (int i = 0; i < dof_; ++i) worst = std::max(worst, std::abs(d()->qvel[dofAt(dof_ + i)]));
    return worst;
  }

  std::string unsound() const override {
    // A non-finite or huge (> 1e10) qpos, qvel or qacc: mj_step has already
    // reset the state to q = 0 and stepped on from there.
    const std::pair<mjtWarning, const char*> alarms[] = {
        {mjWARN_BADQPOS, "joint angles"}, {mjWARN_BADQVEL, "joint rates"}, {mjWARN_BADQACC, "accelerations"}};
    for (const auto& [warning, what] : alarms)
      if (d()->warning[warning].number > 0)
        return std::string("MuJoCo found its ") + what +
               " no longer finite or beyond 1e10 (and reset the arm to q = 0, which is not motion)";
    // Physics MuJoCo changed to carry on: a mass matrix it had to clamp, or
    // constraint rows it had to drop (both silently wrong from then on).
    if (d()->warning[mjWARN_INERTIA].number > 0)
      return "MuJoCo found the mass matrix not positive definite and clamped it";
    if (d()->warning[mjWARN_CNSTRFULL].number > 0)
      return "MuJoCo ran out of room for the joints' constraints and dropped some";
    for (int i = 0; i < model_->nq; ++i)
      if (!std::isfinite(d()->qpos[i])) return "the state is no longer finite";
    for (int i = 0; i < model_->nv; ++i)
      if (!std::isfinite(d()->qvel[i])) return "the state is no longer finite";
    return "";
  }

  double jointSeparation() const override { return 0.0; }
  std::string name() const override { return "MuJoCo"; }

 private:
  mjData* d() const { return data_.get(); }
  // Joint k of the model (the links' first, then the rotors'): its qpos and dof addresses.
  int qpos(int k) const { return model_->jnt_qposadr[k]; }
  int dofAt(int k) const { return model_->jnt_dofadr[k]; }

  // What the damping and friction took in this step, from the rates it
  // reached: D q'^2 h for damping, and the friction constraint's force times
  // the rate. An estimate of O(h), as ODE's is from its motors' torques.
  void addDissipation() {
    const double h = model_->opt.timestep;
    for (int v = 0; v < model_->nv; ++v)
      dissipated_ += model_->dof_damping[v] * d()->qvel[v] * d()->qvel[v] * h;
    for (int r = 0; r < d()->nefc; ++r)
      if (d()->efc_type[r] == mjCNSTR_FRICTION_DOF)
        dissipated_ -= d()->efc_force[r] * d()->qvel[d()->efc_id[r]] * h;
  }

  int dof_;
  std::optional<model::FlexibleParams> flexible_;
  JointPhysics joints_;
  Eigen::Vector3d gravity_;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_, probe_;
  double dissipated_ = 0.0;
};

}  // namespace

std::unique_ptr<PhysicsEngine> makeMujocoEngine(const EngineSetup& setup) {
  return std::make_unique<MujocoEngine>(setup);
}

}  // namespace lagrange::plant
