// A plant from outside the project, in C++: the two-link planar arm of
// configs/rigid_2dof.yaml (the Pelican arm of Kelly, Santibanez and Loria)
// integrated by classical fourth-order Runge-Kutta -- the model and the
// integrator of examples/external_plant/two_link_plant.py, operation for
// operation, so the two agree to rounding -- with the contract kept by
// lagrange's C++ SDK (find_package(lagrange); lagrange::sdk::runPlant).
//
//   M(q) q'' + C(q, q') q' + g(q) = tau,
//
// q_1 measured from the downward vertical, q_2 relative to link 1; each
// link's mass, length, centre of mass and inertia about it are read from the
// resolved scenario (robot.links, robot.gravity), the start from its
// initial_state, the torque held over each period. In a scenario:
//
//   plant: {type: external, command: [/tmp/arm/two_link_plant]}
//
// Options: --substeps N (RK4 steps per period, default 4); --torque-limit,
// --position-limit, --rate-limit, --watchdog-periods: the guards of a bridge
// to a real arm (lagrange::sdk::PlantLimits; docs/hardware.md), off by default.
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/sdk/external_plant.hpp"
#include "lagrange/sdk/scenario.hpp"

namespace {

using State = std::array<double, 4>;  // q1, q2, q1', q2'

// The products are grouped as the Python example's are: the same roundings.
class TwoLinkArm {
 public:
  TwoLinkArm(const nlohmann::json& links, double gravity) : g_(gravity) {
    if (links.size() != 2)
      throw lagrange::sdk::ContractError("the scenario's arm has " + std::to_string(links.size()) +
                                         " links; expected 2");
    m1_ = links[0].at("mass").get<double>();
    l1_ = links[0].at("length").get<double>();
    lc1_ = links[0].at("com").get<double>();
    i1_ = links[0].at("inertia").get<double>();
    m2_ = links[1].at("mass").get<double>();
    lc2_ = links[1].at("com").get<double>();
    i2_ = links[1].at("inertia").get<double>();
  }

  lagrange::sdk::PlantState state(const State& x) const {
    const auto [kinetic, potential] = energy(x);
    return {{x[0], x[1]}, {x[2], x[3]}, kinetic, potential};
  }

  // One classical RK4 step of h seconds under the torque tau.
  State rk4(const State& x, const std::vector<double>& tau, double h) const {
    const State k1 = derivative(x, tau);
    const State k2 = derivative(along(x, k1, 0.5 * h), tau);
    const State k3 = derivative(along(x, k2, 0.5 * h), tau);
    const State k4 = derivative(along(x, k3, h), tau);
    State out{};
    for (size_t i = 0; i < 4; ++i) out[i] = x[i] + h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    return out;
  }

 private:
  std::array<double, 3> massMatrix(double q2) const {
    const double c2 = std::cos(q2);
    const double m11 =
        m1_ * (lc1_ * lc1_) + m2_ * (l1_ * l1_ + lc2_ * lc2_ + 2 * l1_ * lc2_ * c2) + i1_ + i2_;
    const double m12 = m2_ * (lc2_ * lc2_ + l1_ * lc2_ * c2) + i2_;
    const double m22 = m2_ * (lc2_ * lc2_) + i2_;
    return {m11, m12, m22};
  }

  State derivative(const State& x, const std::vector<double>& tau) const {
    const auto [m11, m12, m22] = massMatrix(x[1]);
    const double h = m2_ * l1_ * lc2_ * std::sin(x[1]);
    const double coriolis1 = -h * (2 * x[2] * x[3] + x[3] * x[3]), coriolis2 = h * (x[2] * x[2]);
    const double s1 = std::sin(x[0]), s12 = std::sin(x[0] + x[1]);
    const double gravity1 = (m1_ * lc1_ + m2_ * l1_) * g_ * s1 + m2_ * lc2_ * g_ * s12;
    const double gravity2 = m2_ * lc2_ * g_ * s12;
    const double r1 = tau[0] - coriolis1 - gravity1, r2 = tau[1] - coriolis2 - gravity2;
    const double det = m11 * m22 - m12 * m12;
    return {x[2], x[3], (m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det};
  }

  static State along(const State& x, const State& k, double step) {
    State out{};
    for (size_t i = 0; i < 4; ++i) out[i] = x[i] + step * k[i];
    return out;
  }

  std::pair<double, double> energy(const State& x) const {
    const auto [m11, m12, m22] = massMatrix(x[1]);
    const double kinetic = 0.5 * (m11 * (x[2] * x[2]) + 2 * m12 * x[2] * x[3] + m22 * (x[3] * x[3]));
    const double potential =
        -((m1_ * lc1_ + m2_ * l1_) * g_ * std::cos(x[0]) + m2_ * lc2_ * g_ * std::cos(x[0] + x[1]));
    return {kinetic, potential};
  }

  double m1_, l1_, lc1_, i1_, m2_, lc2_, i2_, g_;
};

// "1.5,2": comma-separated numbers.
std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

// The guards the options ask for; none without any.
std::optional<lagrange::sdk::PlantLimits> limitsOf(const std::map<std::string, std::string>& options) {
  lagrange::sdk::PlantLimits limits;
  if (options.count("--torque-limit")) limits.torque = numbers(options.at("--torque-limit"));
  if (options.count("--rate-limit")) limits.rate = numbers(options.at("--rate-limit"));
  if (options.count("--position-limit")) {
    const std::vector<double> bounds = numbers(options.at("--position-limit"));
    limits.position.emplace();
    for (size_t i = 0; i + 1 < bounds.size(); i += 2) limits.position->emplace_back(bounds[i], bounds[i + 1]);
  }
  if (!limits.torque && !limits.rate && !limits.position) return std::nullopt;
  return limits;
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> options;
  for (int i = 1; i + 1 < argc; i += 2) options[argv[i]] = argv[i + 1];
  int substeps = 4;
  lagrange::sdk::PlantOptions plant;
  try {
    if (argc % 2 == 0) throw std::invalid_argument(std::string("no value after ") + argv[argc - 1]);
    for (const auto& [name, value] : options)
      if (name != "--substeps" && name != "--torque-limit" && name != "--position-limit" &&
          name != "--rate-limit" && name != "--watchdog-periods")
        throw std::invalid_argument("unknown option " + name);
    if (options.count("--substeps")) substeps = std::stoi(options["--substeps"]);
    if (substeps < 1) throw std::invalid_argument("--substeps must be >= 1");
    if (options.count("--watchdog-periods"))
      plant.watchdog_periods = std::stoi(options["--watchdog-periods"]);
    plant.limits = limitsOf(options);
  } catch (const std::exception& e) {
    std::cerr << "two_link_plant: " << e.what()
              << "; expected [--substeps N] [--torque-limit U1,U2] [--position-limit LO1,HI1,LO2,HI2] "
                 "[--rate-limit V1,V2] [--watchdog-periods N]\n";
    return 2;
  }

  std::optional<TwoLinkArm> arm;
  State x{};
  try {
    const nlohmann::json s = lagrange::sdk::scenario();
    arm.emplace(s.at("robot").at("links"), s.at("robot").at("gravity").get<double>());
    const auto q = s.at("initial_state").at("q").get<std::vector<double>>();
    const auto qdot = s.at("initial_state").at("qdot").get<std::vector<double>>();
    if (q.size() != 2 || qdot.size() != 2)
      throw lagrange::sdk::ContractError("the scenario's initial_state is not of two joints");
    x = {q[0], q[1], qdot[0], qdot[1]};
  } catch (const std::exception& e) {
    std::cerr << "two_link_plant: " << e.what() << "\n";
    return 1;
  }

  plant.initial = [&] { return arm->state(x); };
  return lagrange::sdk::runPlant(
      [&](double, const std::vector<double>& u, double dt) {
        const double h = dt / substeps;
        for (int i = 0; i < substeps; ++i) x = arm->rk4(x, u, h);
        return arm->state(x);
      },
      plant);
}
