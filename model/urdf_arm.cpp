#include "model/urdf_arm.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <mutex>
#include <sstream>

#include "model/urdf_tree.hpp"
#include "util/enum_names.hpp"
#include "util/error.hpp"

namespace lagrange::model {

namespace {

KDL::Frame toKdl(const urdf::Pose& p) {
  return KDL::Frame(KDL::Rotation::Quaternion(p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w),
                    KDL::Vector(p.position.x, p.position.y, p.position.z));
}

// A link's inertia in the link's frame: URDF gives it about the centre of
// mass in the <inertial><origin> frame; KDL wants it about the centre of mass
// in the link frame.
KDL::RigidBodyInertia toKdl(const urdf::InertialSharedPtr& i) {
  if (!i) return KDL::RigidBodyInertia::Zero();
  const KDL::Frame origin = toKdl(i->origin);
  const KDL::RotationalInertia in_origin(i->ixx, i->iyy, i->izz, i->ixy, i->ixz, i->iyz);
  return origin * KDL::RigidBodyInertia(i->mass, KDL::Vector::Zero(), in_origin);
}

bool isArmJoint(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS;
}

// urdf::Joint's type is an unnamed enum: its values as int.
constexpr util::EnumName<int> kJointTypeNames[] = {{urdf::Joint::UNKNOWN, "unknown"},
                                                   {urdf::Joint::REVOLUTE, "revolute"},
                                                   {urdf::Joint::CONTINUOUS, "continuous"},
                                                   {urdf::Joint::PRISMATIC, "prismatic"},
                                                   {urdf::Joint::FLOATING, "floating"},
                                                   {urdf::Joint::PLANAR, "planar"},
                                                   {urdf::Joint::FIXED, "fixed"}};
const char* typeName(int type) { return util::nameOf(kJointTypeNames, type); }

std::string number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

std::string moments(const Eigen::Vector3d& m) {
  std::ostringstream out;
  out << m(0) << ", " << m(1) << ", " << m(2);
  return out.str();
}

// A link's <inertial>, checked, in the link's frame. Accepted: no <inertial>
// or mass 0 with a zero tensor (a massless frame, as URDFs write tool and
// flange frames); a positive mass with a positive definite tensor whose
// principal moments obey the triangle inequality (each at most the sum of the
// other two: a rigid body's mass cannot be distributed otherwise). A flat
// plate, the largest moment equal to the sum of the others, passes (1e-9
// relative for rounding); a thin rod, one moment zero, is refused as not
// definite.
KDL::RigidBodyInertia linkInertia(const urdf::Link& link, const std::string& where) {
  const urdf::InertialSharedPtr& i = link.inertial;
  if (!i) return KDL::RigidBodyInertia::Zero();
  const std::string what = where + ": link '" + link.name + "': ";
  Eigen::Matrix3d tensor;
  tensor << i->ixx, i->ixy, i->ixz, i->ixy, i->iyy, i->iyz, i->ixz, i->iyz, i->izz;
  if (!std::isfinite(i->mass) || !tensor.allFinite())
    throw BadInput(what +
                   "<inertial> has a value that is not a finite number; expected finite mass and inertia");
  if (i->mass < 0.0)
    throw BadInput(what + "mass " + number(i->mass) +
                   " kg; expected a positive mass (or 0 for a massless frame)");
  if (i->mass == 0.0) {
    if (!tensor.isZero(0.0))
      throw BadInput(
          what +
          "mass 0 with a non-zero inertia tensor; expected a positive mass, or a zero tensor for a "
          "massless frame");
    return KDL::RigidBodyInertia::Zero();
  }
  const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor).eigenvalues();
  if (m(0) <= 0.0)
    throw BadInput(what + "the inertia tensor is not positive definite (principal moments " + moments(m) +
                   " kg m^2); expected all three positive");
  if (m(2) > (m(0) + m(1)) * (1.0 + 1e-9))
    throw BadInput(what + "the inertia tensor's principal moments " + moments(m) +
                   " kg m^2 violate the triangle inequality (the largest exceeds the sum of the other two); "
                   "expected the moments of a physical body");
  return toKdl(i);
}

// The inertia of a whole subtree, every joint in it held at zero, in the
// frame of its root link.
KDL::RigidBodyInertia subtreeInertia(const urdf::Link& link, const std::string& where) {
  KDL::RigidBodyInertia total = linkInertia(link, where);
  for (const urdf::LinkSharedPtr& child : link.child_links)
    total =
        total + toKdl(child->parent_joint->parent_to_joint_origin_transform) * subtreeInertia(*child, where);
  return total;
}

Eigen::Matrix3d toEigen(const KDL::RotationalInertia& i) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(i.data);
}
Eigen::Vector3d toEigen(const KDL::Vector& v) { return {v.x(), v.y(), v.z()}; }

KDL::JntArray toKdl(const Eigen::VectorXd& v) {
  KDL::JntArray out(static_cast<unsigned>(v.size()));
  out.data = v;
  return out;
}

// urdfdom reports why a document is refused through console_bridge, which
// prints to stderr by default: collect its words for our error message
// instead. The handler is process-wide state, set only for the parse.
class ParserMessages : public console_bridge::OutputHandler {
 public:
  std::string text;
  urdf::ModelInterfaceSharedPtr parse(const std::string& xml) {
    console_bridge::useOutputHandler(this);
    struct Restore {  // also when urdfdom throws: never leave a handler that is gone
      ~Restore() { console_bridge::restorePreviousOutputHandler(); }
    } restore;
    return urdf::parseURDF(xml);
  }
  void log(const std::string& message, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
    text += (text.empty() ? "" : "; ") + message;
  }
};

}  // namespace

struct UrdfArm::Impl {
  UrdfChainSpec spec;
  KDL::Chain chain;
  KDL::Vector gravity;
  std::vector<std::string> joint_names;
  std::vector<std::string> notes;
  std::vector<UrdfJointProperties> joint_properties;
  std::vector<UrdfBody> bodies;

  // KDL's dynamics solvers keep scratch space, so one serves one call at a
  // time; building one per call was a fifth of the gain check's time (it
  // samples C and h at thousands of states). A call borrows a set from this
  // pool and gives it back, which keeps the model safe to share between
  // threads (model/robot_model.hpp's contract). Each call overwrites all the
  // scratch it reads, so a reused solver computes what a fresh one would.
  // The set has its own copy of the chain: a KDL::Joint caches its last pose
  // in mutable members (joint_pose, q_previous) that every pose(q) writes, so
  // one chain read from two threads returned one thread's rotation to the
  // other. `chain` above is only copied after the build, never posed.
  struct Solvers {
    Solvers(const KDL::Chain& c, const KDL::Vector& g) : chain(c), dynamics(chain, g), rne(chain, g) {}
    KDL::Chain chain;  // first: the solvers keep a reference to it
    KDL::ChainDynParam dynamics;
    KDL::ChainIdSolver_RNE rne;
  };
  class Borrowed {
   public:
    Borrowed(Impl& owner, std::unique_ptr<Solvers> solvers) : owner_(owner), solvers_(std::move(solvers)) {}
    Borrowed(const Borrowed&) = delete;
    Borrowed& operator=(const Borrowed&) = delete;
    ~Borrowed() {
      const std::lock_guard<std::mutex> lock(owner_.idle_mutex);
      owner_.idle.push_back(std::move(solvers_));
    }
    Solvers* operator->() const { return solvers_.get(); }

   private:
    Impl& owner_;
    std::unique_ptr<Solvers> solvers_;
  };
  Borrowed borrowSolvers() {
    {
      const std::lock_guard<std::mutex> lock(idle_mutex);
      if (!idle.empty()) {
        std::unique_ptr<Solvers> ready = std::move(idle.back());
        idle.pop_back();
        return Borrowed(*this, std::move(ready));
      }
    }
    return Borrowed(*this, std::make_unique<Solvers>(chain, gravity));
  }
  std::mutex idle_mutex;
  std::vector<std::unique_ptr<Solvers>> idle;
};

std::shared_ptr<const UrdfArm> UrdfArm::build(const UrdfChainSpec& spec) {
  const std::string where = spec.source.empty() ? "robot.urdf" : spec.source;
  ParserMessages messages;
  const urdf::ModelInterfaceSharedPtr robot = messages.parse(spec.xml);
  if (!robot)
    throw BadInput(where + ": not a valid URDF document (urdfdom: " +
                   (messages.text.empty() ? "could not parse it" : messages.text) + ")");
  // urdfdom ties each link to its children with shared_ptrs, so a document
  // whose joints form a loop (refused below) leaves a cycle that would outlive
  // the model: a leak on every such file. Cut the ties when build is done with
  // the model, refused or not; nothing built here keeps urdfdom's links.
  struct CutLinkTies {
    const urdf::ModelInterfaceSharedPtr& model;
    ~CutLinkTies() {
      for (auto& named : model->links_) {
        named.second->child_links.clear();
        named.second->child_joints.clear();
      }
    }
  } cut_link_ties{robot};
  checkUrdfTree(*robot, where);
  auto known_links = [&] {
    std::vector<urdf::LinkSharedPtr> links;
    robot->getLinks(links);
    std::vector<std::string> names;
    for (const auto& l : links) names.push_back(l->name);
    std::sort(names.begin(), names.end());
    std::string list;
    for (size_t i = 0; i < names.size(); ++i) list += (i ? ", " : "") + names[i];
    return list;
  };
  const urdf::LinkConstSharedPtr base = robot->getLink(spec.base_link);
  if (!base)
    throw BadInput(where + ": no link '" + spec.base_link + "' (base_link); its links: " + known_links());
  urdf::LinkConstSharedPtr tip = robot->getLink(spec.tip_link);
  if (!tip)
    throw BadInput(where + ": no link '" + spec.tip_link + "' (tip_link); its links: " + known_links());

  // The path, tip up to base.
  std::vector<urdf::LinkConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr l = tip; l != base; l = l->getParent()) {
    if (!l->getParent()) {
      std::string above;
      for (urdf::LinkConstSharedPtr a = tip->getParent(); a; a = a->getParent())
        above += (above.empty() ? "" : ", ") + a->name;
      throw BadInput(where + ": tip_link '" + spec.tip_link + "' is not below base_link '" + spec.base_link +
                     "' (the links above it: " + (above.empty() ? "none" : above) +
                     "); expected two links on one serial chain, the base above the tip");
    }
    path.push_back(l);
  }
  std::reverse(path.begin(), path.end());  // base's child first

  auto impl = std::make_unique<Impl>();
  impl->spec = spec;
  impl->gravity = KDL::Vector(0.0, 0.0, -spec.gravity);
  for (size_t i = 0; i < path.size(); ++i) {
    const urdf::Link& link = *path[i];
    const urdf::Joint& joint = *link.parent_joint;
    if (!isArmJoint(joint) && joint.type != urdf::Joint::FIXED)
      throw BadInput(where + ": joint '" + joint.name + "' on the chain from '" + spec.base_link + "' to '" +
                     spec.tip_link + "' is " + typeName(joint.type) +
                     "; expected revolute, continuous or fixed");
    // The link with every branch off the chain lumped into it.
    KDL::RigidBodyInertia inertia = linkInertia(link, where);
    const urdf::LinkConstSharedPtr next = i + 1 < path.size() ? path[i + 1] : nullptr;
    for (const urdf::LinkSharedPtr& child : link.child_links) {
      if (child == next) continue;
      inertia = inertia +
                toKdl(child->parent_joint->parent_to_joint_origin_transform) * subtreeInertia(*child, where);
      impl->notes.push_back("joint '" + child->parent_joint->name + "' (" +
                            typeName(child->parent_joint->type) + ") is off the chain: held at 0, link '" +
                            child->name +
                            "' and what hangs from it "
                            "lumped into '" +
                            link.name + "'");
    }
    const KDL::Frame origin = toKdl(joint.parent_to_joint_origin_transform);
    KDL::Joint kdl_joint(joint.name, KDL::Joint::None);
    if (isArmJoint(joint)) {
      const KDL::Vector axis(joint.axis.x, joint.axis.y, joint.axis.z);
      kdl_joint = KDL::Joint(joint.name, origin.p, origin.M * axis, KDL::Joint::RotAxis);
      impl->joint_names.push_back(joint.name);
      UrdfJointProperties props;
      std::ostringstream unused;
      if (joint.limits) {
        // urdfdom reads an absent lower or upper as 0, and files write
        // lower = upper = 0 for "no limits" (robots/double_pendulum.urdf): a
        // stop is taken only from lower < upper. An effort or velocity of 0
        // would stop the joint, so 0 is taken as "not given" too.
        if (joint.limits->effort > 0.0) props.effort = joint.limits->effort;
        if (joint.limits->velocity > 0.0) props.velocity = joint.limits->velocity;
        if (joint.type == urdf::Joint::REVOLUTE && joint.limits->lower < joint.limits->upper) {
          props.lower = joint.limits->lower;
          props.upper = joint.limits->upper;
          unused << " <limit lower=" << joint.limits->lower << " upper=" << joint.limits->upper << ">";
        }
      }
      if (joint.dynamics) {
        props.damping = joint.dynamics->damping;
        props.friction = joint.dynamics->friction;
        if (props.damping != 0.0 || props.friction != 0.0)
          unused << " <dynamics damping=" << joint.dynamics->damping
                 << " friction=" << joint.dynamics->friction << ">";
      }
      impl->joint_properties.push_back(props);
      if (!unused.str().empty())
        impl->notes.push_back("joint '" + joint.name + "':" + unused.str() +
                              " not in the controllers' model (lossless, eq. (1), without joint limits); the "
                              "plant applies them only when asked (plant.urdf_dynamics, plant.joint_limits)");
    }
    impl->chain.addSegment(KDL::Segment(link.name, kdl_joint, origin, inertia));
  }
  if (impl->joint_names.empty())
    throw BadInput(where + ": no revolute or continuous joint between '" + spec.base_link + "' and '" +
                   spec.tip_link + "'");

  // The moving bodies at q = 0: fixed segments merged into the body before them.
  KDL::Frame frame = KDL::Frame::Identity();
  // Fixed segments before the first joint belong to the base: they never move.
  std::vector<KDL::RigidBodyInertia> body_inertia;  // in the base frame
  for (const KDL::Segment& segment : impl->chain.segments) {
    const KDL::Frame joint_frame = frame;  // the parent's frame: the joint's origin and axis are in it
    frame = frame * segment.pose(0.0);
    const KDL::RigidBodyInertia in_base = frame * segment.getInertia();
    if (segment.getJoint().getType() == KDL::Joint::None) {
      if (!body_inertia.empty()) body_inertia.back() = body_inertia.back() + in_base;
      continue;
    }
    UrdfBody body;
    body.link = segment.getName();
    body.joint = segment.getJoint().getName();
    body.joint_anchor = toEigen(joint_frame * segment.getJoint().JointOrigin());
    body.joint_axis = toEigen(joint_frame.M * segment.getJoint().JointAxis()).normalized();
    impl->bodies.push_back(body);
    body_inertia.push_back(in_base);
  }
  for (size_t b = 0; b < impl->bodies.size(); ++b) {
    KDL::RigidBodyInertia in_base = body_inertia[b];
    UrdfBody& body = impl->bodies[b];
    body.mass = in_base.getMass();
    // ODE needs a positive mass in every moving body, and D(q) would be
    // singular without one.
    if (!(body.mass > 0.0))
      throw BadInput(
          where + ": joint '" + body.joint + "' moves no mass (link '" + body.link +
          "' and the links fixed to it are massless); expected a positive mass on every moving body");
    const KDL::Vector com = body.mass > 0.0 ? in_base.getCOG() : KDL::Vector::Zero();
    body.com = toEigen(com);
    // KDL keeps the rotational inertia about the frame's origin: move it to the centre of mass.
    body.inertia = toEigen(in_base.RefPoint(com).getRotationalInertia());
  }
  return std::shared_ptr<const UrdfArm>(new UrdfArm(std::move(impl)));
}

UrdfArm::UrdfArm(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
UrdfArm::~UrdfArm() = default;

int UrdfArm::dof() const { return static_cast<int>(impl_->joint_names.size()); }
std::vector<std::string> UrdfArm::jointNames() const { return impl_->joint_names; }
const std::vector<std::string>& UrdfArm::notes() const { return impl_->notes; }
const std::vector<UrdfJointProperties>& UrdfArm::jointProperties() const { return impl_->joint_properties; }
const std::vector<UrdfBody>& UrdfArm::bodies() const { return impl_->bodies; }
const UrdfChainSpec& UrdfArm::spec() const { return impl_->spec; }

RobotGeometry UrdfArm::geometry() const {
  RobotGeometry g;
  int joint = 0;
  const Impl::Borrowed solvers = impl_->borrowSolvers();  // getFrameToTip poses the joint at 0
  for (const KDL::Segment& segment : solvers->chain.segments) {
    GeometryFrame f;
    f.parent = static_cast<int>(g.frames.size()) - 1;
    // The segment's pose at q = 0 is the URDF joint's origin; KDL keeps the
    // axis in the parent frame, the frame's own axis is rotated back.
    const KDL::Frame origin = segment.getFrameToTip();
    f.origin_xyz = toEigen(origin.p);
    double x, y, z, w;
    origin.M.GetQuaternion(x, y, z, w);
    f.origin_quat = Eigen::Quaterniond(w, x, y, z);
    if (segment.getJoint().getType() != KDL::Joint::None) {
      f.joint = joint++;
      f.axis = toEigen(origin.M.Inverse(segment.getJoint().JointAxis())).normalized();
    }
    g.frames.push_back(f);
  }
  g.tip_frame = static_cast<int>(g.frames.size()) - 1;
  g.up = Eigen::Vector3d::UnitZ();
  addSkeletonShapes(g);
  return g;
}

Eigen::Vector3d UrdfArm::tipPosition(const Eigen::VectorXd& q) const { return tipFrame(q).translation(); }

Eigen::Isometry3d UrdfArm::tipFrame(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const Impl::Borrowed solvers = impl_->borrowSolvers();
  KDL::ChainFkSolverPos_recursive fk(solvers->chain);
  KDL::Frame tip;
  fk.JntToCart(toKdl(q), tip);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out.linear()(r, c) = tip.M(static_cast<unsigned>(r), static_cast<unsigned>(c));
  out.translation() = toEigen(tip.p);
  return out;
}

// The dynamics below borrow KDL's solvers from the arm's pool (Impl::borrowSolvers).
Eigen::MatrixXd UrdfArm::inertia(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  KDL::JntSpaceInertiaMatrix d(static_cast<unsigned>(dof()));
  impl_->borrowSolvers()->dynamics.JntToMass(toKdl(q), d);
  return d.data;
}

Eigen::VectorXd UrdfArm::velocityTerms(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  checkSize(q, "q");
  checkSize(v, "v");
  KDL::JntArray h(static_cast<unsigned>(dof()));
  impl_->borrowSolvers()->dynamics.JntToCoriolis(toKdl(q), toKdl(v), h);
  return h.data;
}

Eigen::VectorXd UrdfArm::coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& w) const {
  checkSize(w, "w");
  return 0.25 * (velocityTerms(q, v + w) - velocityTerms(q, v - w));
}

Eigen::MatrixXd UrdfArm::coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  const int n = dof();
  Eigen::MatrixXd c(n, n);
  for (int j = 0; j < n; ++j) c.col(j) = coriolisTimes(q, v, Eigen::VectorXd::Unit(n, j));
  return c;
}

std::vector<Eigen::MatrixXd> UrdfArm::coriolisPerVelocity(const Eigen::VectorXd& q) const {
  // C_k e_j = C(q, e_k) e_j = (h(e_k + e_j) - h(e_k) - h(e_j)) / 2 (h is a
  // quadratic form in v), symmetric in k and j: n (n + 1) / 2 KDL calls where
  // polarisation column by column takes 2 n^2. The gain reports sample C at
  // thousands of states (model/bounds.hpp), which this makes 3.5x cheaper.
  const int n = dof();
  std::vector<Eigen::VectorXd> diagonal(n);
  for (int k = 0; k < n; ++k) diagonal[k] = velocityTerms(q, Eigen::VectorXd::Unit(n, k));
  std::vector<Eigen::MatrixXd> ck(n, Eigen::MatrixXd(n, n));
  for (int k = 0; k < n; ++k) {
    ck[k].col(k) = diagonal[k];
    for (int j = k + 1; j < n; ++j) {
      const Eigen::VectorXd column =
          0.5 * (velocityTerms(q, Eigen::VectorXd::Unit(n, k) + Eigen::VectorXd::Unit(n, j)) - diagonal[k] -
                 diagonal[j]);
      ck[k].col(j) = column;
      ck[j].col(k) = column;
    }
  }
  return ck;
}

Eigen::VectorXd UrdfArm::gravity(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  KDL::JntArray g(static_cast<unsigned>(dof()));
  impl_->borrowSolvers()->dynamics.JntToGravity(toKdl(q), g);
  return g.data;
}

double UrdfArm::potentialEnergy(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  KDL::Frame frame = KDL::Frame::Identity();
  double u = 0.0;
  int j = 0;
  const Impl::Borrowed solvers = impl_->borrowSolvers();
  for (const KDL::Segment& segment : solvers->chain.segments) {
    const bool moves = segment.getJoint().getType() != KDL::Joint::None;
    frame = frame * segment.pose(moves ? q(j++) : 0.0);
    const KDL::RigidBodyInertia& inertia = segment.getInertia();
    if (inertia.getMass() > 0.0)
      u += inertia.getMass() * impl_->spec.gravity * (frame * inertia.getCOG()).z();
  }
  return u;
}

Eigen::VectorXd UrdfArm::inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& a) const {
  checkSize(q, "q");
  checkSize(v, "v");
  checkSize(a, "a");
  KDL::JntArray tau(static_cast<unsigned>(dof()));
  const KDL::Wrenches no_external(impl_->chain.getNrOfSegments(), KDL::Wrench::Zero());
  if (impl_->borrowSolvers()->rne.CartToJnt(toKdl(q), toKdl(v), toKdl(a), no_external, tau) < 0)
    throw lagrange::RuntimeFault("urdf model: KDL's inverse dynamics failed");
  return tau.data;
}
}  // namespace lagrange::model
