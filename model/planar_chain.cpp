#include "model/planar_chain.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lagrange::model {

ChainParams pelicanParams() {
  ChainParams p;
  p.links = {{0.26, 0.0983, 6.5225, 0.1213}, {0.26, 0.0229, 2.0458, 0.01616}};
  p.gravity = 9.81;
  return p;
}

PlanarChain::PlanarChain(ChainParams params) : params_(std::move(params)) {
  const int n = dof();
  if (n < 1) throw std::invalid_argument("PlanarChain: at least one link is needed");
  for (int i = 0; i < n; ++i) {
    const LinkParams& l = params_.links[i];
    const std::string which = "PlanarChain: link " + std::to_string(i + 1) + ": ";
    if (!(l.length > 0.0) || !std::isfinite(l.length))
      throw std::invalid_argument(which + "length must be positive and finite");
    if (!(l.mass > 0.0) || !std::isfinite(l.mass))
      throw std::invalid_argument(which + "mass must be positive and finite");
    if (!(l.inertia > 0.0) || !std::isfinite(l.inertia))
      throw std::invalid_argument(which + "inertia must be positive and finite");
    if (!(l.com >= 0.0) || !std::isfinite(l.com))
      throw std::invalid_argument(which + "com must be non-negative and finite");
  }
  if (!std::isfinite(params_.gravity)) throw std::invalid_argument("PlanarChain: gravity must be finite");

  // c(i, a): lever arm of absolute angle a in the centre of mass of link i.
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < i; ++a) c(i, a) = params_.links[a].length;
    c(i, i) = params_.links[i].com;
  }
  Eigen::VectorXd m(n);
  for (int i = 0; i < n; ++i) m(i) = params_.links[i].mass;
  h_ = c.transpose() * m.asDiagonal() * c;
  s_ = c.transpose() * m;
}

std::vector<std::string> PlanarChain::jointNames() const {
  std::vector<std::string> names;
  for (int i = 1; i <= dof(); ++i) names.push_back("joint" + std::to_string(i));
  return names;
}

Eigen::VectorXd PlanarChain::absoluteAngles(const Eigen::VectorXd& q) const {
  Eigen::VectorXd phi(q.size());
  double sum = 0.0;
  for (int i = 0; i < q.size(); ++i) phi(i) = (sum += q(i));
  return phi;
}

namespace {
// D = L^T M L with L lower-triangular ones: D_jk = sum_{a>=j, b>=k} M_ab,
// computed with suffix sums in O(n^2).
Eigen::MatrixXd congruenceWithOnes(const Eigen::MatrixXd& m) {
  const int n = static_cast<int>(m.rows());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
  for (int j = n - 1; j >= 0; --j) {
    for (int k = n - 1; k >= 0; --k) {
      d(j, k) = m(j, k) + (j + 1 < n ? d(j + 1, k) : 0.0) + (k + 1 < n ? d(j, k + 1) : 0.0) -
                (j + 1 < n && k + 1 < n ? d(j + 1, k + 1) : 0.0);
    }
  }
  return d;
}
}  // namespace

Eigen::MatrixXd PlanarChain::inertia(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const int n = dof();
  const Eigen::VectorXd phi = absoluteAngles(q);
  Eigen::MatrixXd m(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) m(a, b) = h_(a, b) * std::cos(phi(a) - phi(b));
  for (int a = 0; a < n; ++a) m(a, a) += params_.links[a].inertia;
  return congruenceWithOnes(m);
}

std::vector<Eigen::MatrixXd> PlanarChain::inertiaPartials(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const int n = dof();
  const Eigen::VectorXd phi = absoluteAngles(q);
  // dM_ab/dq_k = -h_ab sin(phi_a - phi_b) (L_ak - L_bk), L_ak = 1 iff k <= a.
  std::vector<Eigen::MatrixXd> partials;
  partials.reserve(n);
  for (int k = 0; k < n; ++k) {
    Eigen::MatrixXd dm = Eigen::MatrixXd::Zero(n, n);
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        const int selector = (k <= a ? 1 : 0) - (k <= b ? 1 : 0);
        if (selector != 0) dm(a, b) = -h_(a, b) * std::sin(phi(a) - phi(b)) * selector;
      }
    }
    partials.push_back(congruenceWithOnes(dm));
  }
  return partials;
}

std::vector<Eigen::MatrixXd> PlanarChain::coriolisPerVelocity(const Eigen::VectorXd& q) const {
  const int n = dof();
  const std::vector<Eigen::MatrixXd> dd = inertiaPartials(q);
  // Christoffel symbols: c_ijk = (dD_ij/dq_k + dD_ik/dq_j - dD_jk/dq_i) / 2.
  std::vector<Eigen::MatrixXd> ck(n, Eigen::MatrixXd::Zero(n, n));
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) ck[k](i, j) = 0.5 * (dd[k](i, j) + dd[j](i, k) - dd[i](j, k));
  return ck;
}

std::optional<std::vector<CoriolisTerm>> PlanarChain::coriolisTerms() const {
  const int n = dof();
  std::vector<CoriolisTerm> terms;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (h_(a, b) == 0.0) continue;
      // inertiaPartials with only the (a, b) and (b, a) entries, sin(phi_a - phi_b)
      // factored out: dM_ab/dq_k = dM_ba/dq_k = -h_ab (L_ak - L_bk).
      std::vector<Eigen::MatrixXd> dd(n);
      for (int k = 0; k < n; ++k) {
        Eigen::MatrixXd dm = Eigen::MatrixXd::Zero(n, n);
        const int selector = (k <= a ? 1 : 0) - (k <= b ? 1 : 0);
        dm(a, b) = dm(b, a) = -h_(a, b) * selector;
        dd[k] = congruenceWithOnes(dm);
      }
      CoriolisTerm term{a, b, std::vector<Eigen::MatrixXd>(n, Eigen::MatrixXd::Zero(n, n))};
      for (int k = 0; k < n; ++k)
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            term.per_velocity[k](i, j) = 0.5 * (dd[k](i, j) + dd[j](i, k) - dd[i](j, k));
      terms.push_back(std::move(term));
    }
  }
  return terms;
}

Eigen::VectorXd PlanarChain::jointTorques(const Eigen::ArrayXd& absolute) {
  Eigen::VectorXd out(absolute.size());
  double suffix = 0.0;
  for (Eigen::Index i = absolute.size() - 1; i >= 0; --i) out(i) = (suffix += absolute(i));
  return out;
}

Eigen::VectorXd PlanarChain::coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& w) const {
  checkSize(q, "q");
  checkSize(v, "v");
  checkSize(w, "w");
  // The velocity terms of inverseDynamics below, in absolute angles, are the
  // quadratic form h(om)_a = sum_b h_ab sin(phi_a - phi_b) om_b^2. Christoffel
  // symbols are symmetric in their two velocity indices, so C(om) nu is the
  // symmetric bilinear form of h: om_b^2 becomes om_b nu_b. The coordinates
  // are linear in q (phi = L q), so C in joint angles is L^T C(L v) L w.
  const Eigen::VectorXd phi = absoluteAngles(q);
  const Eigen::ArrayXd c = phi.array().cos(), s = phi.array().sin(),
                       product = absoluteAngles(v).array() * absoluteAngles(w).array();
  const Eigen::ArrayXd tau =
      s * (h_ * (c * product).matrix()).array() - c * (h_ * (s * product).matrix()).array();
  return jointTorques(tau);
}

Eigen::VectorXd PlanarChain::inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                             const Eigen::VectorXd& a) const {
  checkSize(q, "q");
  checkSize(v, "v");
  checkSize(a, "a");
  const int n = dof();
  // In absolute angles phi = L q (rates w = L v, accelerations al = L a) the
  // Euler-Lagrange equations of M_ab = I_a delta_ab + h_ab cos(phi_a - phi_b) are
  //   tau_a = I_a al_a + sum_b h_ab (cos(phi_a - phi_b) al_b + sin(phi_a - phi_b) w_b^2) + g s_a sin(phi_a),
  // and the joint torques are L^T tau (suffix sums). With cos(x - y) =
  // cx cy + sx sy and sin(x - y) = sx cy - cx sy this is four products with
  // h: O(n^2), where D a + C v v from the Christoffel partials is O(n^4).
  const Eigen::VectorXd phi = absoluteAngles(q), w = absoluteAngles(v), al = absoluteAngles(a);
  const Eigen::ArrayXd c = phi.array().cos(), s = phi.array().sin(), w2 = w.array().square();
  Eigen::ArrayXd inertia(n);
  for (int i = 0; i < n; ++i) inertia(i) = params_.links[i].inertia;
  const Eigen::ArrayXd tau = inertia * al.array() + c * (h_ * (c * al.array()).matrix()).array() +
                             s * (h_ * (s * al.array()).matrix()).array() +
                             s * (h_ * (c * w2).matrix()).array() - c * (h_ * (s * w2).matrix()).array() +
                             params_.gravity * s_.array() * s;
  return jointTorques(tau);
}

Eigen::VectorXd PlanarChain::gravity(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const Eigen::VectorXd phi = absoluteAngles(q);
  // dU/dphi_a = g s_a sin(phi_a); dU/dq_k = sum_{a >= k} dU/dphi_a.
  Eigen::VectorXd out(dof());
  double suffix = 0.0;
  for (int a = dof() - 1; a >= 0; --a) {
    suffix += params_.gravity * s_(a) * std::sin(phi(a));
    out(a) = suffix;
  }
  return out;
}

RobotGeometry PlanarChain::geometry() const {
  RobotGeometry g;
  for (int i = 0; i < dof(); ++i) {
    GeometryFrame f;
    f.parent = i - 1;
    f.joint = i;
    if (i > 0) f.origin_xyz = {0.0, -params_.links[i - 1].length, 0.0};
    f.axis = Eigen::Vector3d::UnitZ();
    g.frames.push_back(f);
  }
  g.tip_frame = dof() - 1;
  g.tip_xyz = {0.0, -params_.links.back().length, 0.0};
  g.up = Eigen::Vector3d::UnitY();
  g.plane_normal = Eigen::Vector3d::UnitZ();
  addSkeletonShapes(g);
  return g;
}

Eigen::Vector3d PlanarChain::tipPosition(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const Eigen::VectorXd phi = absoluteAngles(q);
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  for (int i = 0; i < dof(); ++i)
    tip += params_.links[i].length * Eigen::Vector3d(std::sin(phi(i)), -std::cos(phi(i)), 0.0);
  return tip;
}

double PlanarChain::potentialEnergy(const Eigen::VectorXd& q) const {
  checkSize(q, "q");
  const Eigen::VectorXd phi = absoluteAngles(q);
  double u = 0.0;
  for (int a = 0; a < dof(); ++a) u -= params_.gravity * s_(a) * std::cos(phi(a));
  return u;
}

}  // namespace lagrange::model
