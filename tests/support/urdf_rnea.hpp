#pragma once
// A second derivation of a URDF arm's dynamics, written without the dynamics
// library (KDL) the model uses: urdfdom reads the document, and the recursive
// Newton-Euler algorithm below (Craig, "Introduction to Robotics", 3rd ed.,
// section 6.5, in link frames with gravity as a base acceleration) gives the
// joint torques. Off-chain branches are lumped and fixed joints kept rigid, as
// the model's docs say, by its own composition of rigid bodies.

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::testing {

class UrdfRnea {
 public:
  UrdfRnea(const std::string& xml, const std::string& base, const std::string& tip, double g) : g_(g) {
    const urdf::ModelInterfaceSharedPtr robot = urdf::parseURDF(xml);
    if (!robot) throw std::runtime_error("UrdfRnea: unparsable URDF");
    std::vector<urdf::LinkConstSharedPtr> path;
    for (urdf::LinkConstSharedPtr l = robot->getLink(tip); l->name != base; l = l->getParent())
      path.push_back(l);
    std::reverse(path.begin(), path.end());
    for (size_t i = 0; i < path.size(); ++i) {
      const urdf::Link& link = *path[i];
      const urdf::Joint& joint = *link.parent_joint;
      Link out;
      out.rotation = rotation(joint.parent_to_joint_origin_transform);
      out.position = position(joint.parent_to_joint_origin_transform);
      out.moves = joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS;
      out.axis = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
      out.body = own(link);
      const urdf::LinkConstSharedPtr next = i + 1 < path.size() ? path[i + 1] : nullptr;
      for (const urdf::LinkSharedPtr& child : link.child_links)
        if (child != next)
          out.body = combine(out.body,
                             moved(subtree(*child), child->parent_joint->parent_to_joint_origin_transform));
      links_.push_back(out);
      if (out.moves) ++dof_;
    }
  }

  int dof() const { return dof_; }

  /// tau = D(q) a + C(q, v) v + g(q).
  Eigen::VectorXd torques(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                          const Eigen::VectorXd& a) const {
    const size_t n = links_.size();
    std::vector<Eigen::Matrix3d> r(n);  // frame i in frame i-1
    std::vector<Eigen::Vector3d> w(n), dw(n), acc(n), f(n), m(n), force(n), moment(n);
    Eigen::Vector3d w_prev = Eigen::Vector3d::Zero(), dw_prev = Eigen::Vector3d::Zero();
    Eigen::Vector3d a_prev(0.0, 0.0, g_);  // gravity as an upward acceleration of the base
    int j = 0;
    std::vector<int> joint_of(n, -1);
    for (size_t i = 0; i < n; ++i) {
      const Link& l = links_[i];
      const double qi = l.moves ? q(j) : 0.0, vi = l.moves ? v(j) : 0.0, ai = l.moves ? a(j) : 0.0;
      if (l.moves) joint_of[i] = j++;
      r[i] = l.rotation * Eigen::AngleAxisd(qi, l.axis).toRotationMatrix();
      const Eigen::Matrix3d rt = r[i].transpose();
      acc[i] = rt * (a_prev + dw_prev.cross(l.position) + w_prev.cross(w_prev.cross(l.position)));
      w[i] = rt * w_prev + l.axis * vi;
      dw[i] = rt * dw_prev + l.axis * ai + (rt * w_prev).cross(l.axis * vi);
      const Eigen::Vector3d a_com = acc[i] + dw[i].cross(l.body.com) + w[i].cross(w[i].cross(l.body.com));
      force[i] = l.body.mass * a_com;
      moment[i] = l.body.inertia * dw[i] + w[i].cross(l.body.inertia * w[i]);
      w_prev = w[i];
      dw_prev = dw[i];
      a_prev = acc[i];
    }
    Eigen::VectorXd tau(dof_);
    Eigen::Vector3d f_next = Eigen::Vector3d::Zero(), m_next = Eigen::Vector3d::Zero();
    for (size_t k = n; k-- > 0;) {
      const Eigen::Vector3d f_child =
          k + 1 < n ? Eigen::Vector3d(r[k + 1] * f_next) : Eigen::Vector3d::Zero();
      const Eigen::Vector3d m_child =
          k + 1 < n ? Eigen::Vector3d(r[k + 1] * m_next) : Eigen::Vector3d::Zero();
      const Eigen::Vector3d p_child = k + 1 < n ? links_[k + 1].position : Eigen::Vector3d::Zero();
      f[k] = force[k] + f_child;
      m[k] = moment[k] + m_child + links_[k].body.com.cross(force[k]) + p_child.cross(f_child);
      if (joint_of[k] >= 0) tau(joint_of[k]) = m[k].dot(links_[k].axis);
      f_next = f[k];
      m_next = m[k];
    }
    return tau;
  }

  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(dof_);
    UrdfRnea no_gravity = *this;
    no_gravity.g_ = 0.0;
    Eigen::MatrixXd d(dof_, dof_);
    for (int k = 0; k < dof_; ++k) d.col(k) = no_gravity.torques(q, zero, Eigen::VectorXd::Unit(dof_, k));
    return d;
  }
  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(dof_);
    return torques(q, zero, zero);
  }

 private:
  struct Body {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about com, in the link frame
  };
  struct Link {
    Eigen::Matrix3d rotation;  // the joint's origin in the parent link
    Eigen::Vector3d position;
    Eigen::Vector3d axis;
    bool moves = false;
    Body body;
  };

  static Eigen::Matrix3d rotation(const urdf::Pose& p) {
    return Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  }
  static Eigen::Vector3d position(const urdf::Pose& p) { return {p.position.x, p.position.y, p.position.z}; }
  static Eigen::Matrix3d skewSquared(const Eigen::Vector3d& d) {  // the parallel-axis term
    return d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose();
  }
  static Body own(const urdf::Link& link) {
    Body b;
    if (!link.inertial) return b;
    const urdf::Inertial& i = *link.inertial;
    Eigen::Matrix3d in;
    in << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
    const Eigen::Matrix3d r = rotation(i.origin);
    b.mass = i.mass;
    b.com = position(i.origin);
    b.inertia = r * in * r.transpose();
    return b;
  }
  static Body moved(const Body& b,
                    const urdf::Pose& p) {  // b given in a child frame, returned in the parent's
    const Eigen::Matrix3d r = rotation(p);
    return {b.mass, r * b.com + position(p), r * b.inertia * r.transpose()};
  }
  static Body combine(const Body& x, const Body& y) {
    Body s;
    s.mass = x.mass + y.mass;
    if (s.mass == 0.0) return s;
    s.com = (x.mass * x.com + y.mass * y.com) / s.mass;
    s.inertia =
        x.inertia + x.mass * skewSquared(x.com - s.com) + y.inertia + y.mass * skewSquared(y.com - s.com);
    return s;
  }
  static Body subtree(const urdf::Link& link) {
    Body b = own(link);
    for (const urdf::LinkSharedPtr& child : link.child_links)
      b = combine(b, moved(subtree(*child), child->parent_joint->parent_to_joint_origin_transform));
    return b;
  }

  double g_;
  int dof_ = 0;
  std::vector<Link> links_;
};

}  // namespace lagrange::testing
