// A PD controller from outside the project, in C++: the law of
// examples/external_controller/PdController.java, with the contract kept by
// lagrange's C++ SDK (find_package(lagrange); lagrange::sdk).
//
//   u = -Kp (q - q_d) - Kd v,   v = (q_k - q_{k-1}) / (t_k - t_{k-1}) (0 at the first sample),
//
// with a constant q_d: no model, no gravity compensation -- for an arm
// without gravity (robot.gravity: 0) it regulates to q_d. Without --qd,
// q_d is the scenario's reference.offset, read from the resolved scenario
// the run hands over (lagrange::sdk::scenario()).
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "lagrange/sdk/external_controller.hpp"
#include "lagrange/sdk/scenario.hpp"

namespace {

// "20,5" or "20": one number per joint, or one for every joint.
std::vector<double> perJoint(const std::string& text, size_t joints) {
  std::vector<double> parts;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) parts.push_back(std::stod(item));
  std::vector<double> v(joints);
  for (size_t j = 0; j < joints; ++j) v[j] = parts.at(parts.size() == 1 ? 0 : j);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> options;
  for (int i = 1; i + 1 < argc; i += 2) options[argv[i]] = argv[i + 1];
  const char* joints_text = std::getenv("LAGRANGE_JOINTS");
  if (!options.count("--kp") || !options.count("--kd") || joints_text == nullptr) {
    std::cerr << "pd_controller: expected --kp K --kd K [--qd Q] (one number, or one per joint, "
                 "comma-separated), started by lagrange run (controller.type: external)\n";
    return 2;
  }
  const size_t n = static_cast<size_t>(std::atoi(joints_text));
  const std::vector<double> kp = perJoint(options["--kp"], n), kd = perJoint(options["--kd"], n);
  std::vector<double> qd;
  try {
    qd = options.count("--qd")
             ? perJoint(options["--qd"], n)
             : lagrange::sdk::scenario().at("reference").at("offset").get<std::vector<double>>();
  } catch (const std::exception& e) {
    std::cerr << "pd_controller: no --qd, and the scenario's reference.offset could not be read: " << e.what()
              << "\n";
    return 2;
  }
  std::vector<double> previous_q;
  double previous_t = 0.0;

  const auto step = [&](double t, const std::vector<double>& q) {
    lagrange::sdk::Command c;
    for (size_t j = 0; j < n; ++j) {
      const double v = previous_q.empty() ? 0.0 : (q[j] - previous_q[j]) / (t - previous_t);
      c.q_error.push_back(q[j] - qd[j]);
      c.theta.push_back(v);
      c.u.push_back(-kp[j] * c.q_error[j] - kd[j] * v);
    }
    c.q_desired = qd;
    previous_q = q;
    previous_t = t;
    return c;
  };
  return lagrange::sdk::run(
      step, [&] { previous_q.clear(); }, "pd_controller");
}
