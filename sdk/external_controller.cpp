#include "lagrange/sdk/external_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/status_t.hpp"
#include "sdk/contract.hpp"

namespace lagrange::sdk {

namespace {

constexpr int64_t kKeepAnswers = 64;  // lockstep re-sends only the tick it awaits

class Controller {
 public:
  Controller(const Step& step, const std::function<void()>& reset)
      : step_(step),
        reset_(reset),
        joints_(static_cast<int>(contract::integer("LAGRANGE_JOINTS", "controller"))),
        bus_("controller") {
    bus_.lcm().subscribe("PLANT_POSITION", &Controller::onPosition, this);
    bus_.lcm().subscribe("STATUS", &Controller::onStatus, this);
  }

  int serve() {
    auto next_status = std::chrono::steady_clock::now();
    while (!plant_finished_) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_status) {  // ten times a second until the first position, then twice
        publishStatus(last_tick_ < 0 ? "ready" : "running");
        next_status = now + std::chrono::milliseconds(last_tick_ < 0 ? 100 : 500);
      }
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(
          next_status - std::chrono::steady_clock::now());
      bus_.handle(static_cast<int>(std::max<int64_t>(1, wait.count())));
      if (!error_.empty()) throw ContractError(error_);
    }
    for (int i = 0; i < 3; ++i) publishStatus("finished");
    return 0;
  }

 private:
  void publishCommand(lagrange::control_command_t c) {
    bus_.publish("CONTROL_COMMAND", c, c.header.tick, c.header.sim_time);
  }

  void publishStatus(const std::string& state) {
    lagrange::status_t s{};
    s.process = "controller";
    s.state = state;
    s.last_tick = last_tick_;
    s.tracking_error = std::numeric_limits<double>::quiet_NaN();
    s.num_channels = 0;
    bus_.publish("STATUS", s, last_tick_, 0.0);
  }

  std::vector<double> vector(const std::vector<double>& v, const char* what,
                             const lagrange::plant_position_t& p) const {
    if (v.empty() && std::string(what) != "u") return std::vector<double>(static_cast<size_t>(joints_), 0.0);
    if (static_cast<int>(v.size()) != joints_)
      throw ContractError(std::string("the law returned ") + std::to_string(v.size()) + " numbers for " +
                          what + "; expected " + std::to_string(joints_) + " (one per joint)");
    // The plant would refuse the command and the run stall: say it here, at once.
    for (size_t j = 0; j < v.size(); ++j)
      if (!std::isfinite(v[j]))
        throw ContractError(std::string("the law returned ") + std::to_string(v[j]) + " for " + what + "[" +
                            std::to_string(j) + "] (joint " + std::to_string(j + 1) +
                            ") at the sample of tick " + std::to_string(p.header.tick) +
                            " (t = " + std::to_string(p.header.sim_time) + " s); expected finite numbers");
    return v;
  }

  void onStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::status_t s;
    if (bus_.receive(rbuf, s) != contract::Verdict::kAccepted) return;
    if (s.process == "plant" && s.state == "finished") plant_finished_ = true;
  }

  void onPosition(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (!error_.empty()) return;
    lagrange::plant_position_t p;
    if (bus_.receive(rbuf, p) != contract::Verdict::kAccepted) return;
    if (p.header.publisher != "plant" || p.num_joints != joints_ || static_cast<int>(p.q.size()) != joints_)
      return;
    const int64_t tick = p.header.tick;
    if (const auto cached = answered_.find(tick); cached != answered_.end()) {
      publishCommand(cached->second);  // a re-sent position: the same answer, the law not stepped
      return;
    }
    if (tick <= last_tick_) return;  // older than one answered: never step back
    try {
      if (last_tick_ < 0 && reset_) reset_();
      const Command out = step_(p.header.sim_time, p.q);
      lagrange::control_command_t c{};
      c.header.tick = tick;
      c.header.sim_time = p.header.sim_time;
      c.input_position_tick = tick;
      c.input_actuator_tick = -1;
      c.input_motor_tick = -1;
      c.num_joints = joints_;
      c.u = vector(out.u, "u", p);
      c.q_desired = vector(out.q_desired, "q_desired", p);
      c.q_error = vector(out.q_error, "q_error", p);
      c.theta = vector(out.theta, "theta", p);
      c.filter_state = vector(out.filter_state, "filter_state", p);
      c.chain_order = 0;
      answered_[tick] = c;
      answered_.erase(answered_.begin(), answered_.upper_bound(tick - kKeepAnswers));  // skipped ticks too
      last_tick_ = tick;
      publishCommand(c);
    } catch (const std::exception& e) {  // not through LCM's C frames: serve() throws it
      error_ = e.what();
    }
  }

  Step step_;
  std::function<void()> reset_;
  int joints_;
  contract::Bus bus_;
  std::map<int64_t, lagrange::control_command_t> answered_;
  int64_t last_tick_ = -1;
  bool plant_finished_ = false;
  std::string error_;
};

}  // namespace

int run(const Step& step, const std::function<void()>& reset, const std::string& program) {
  try {
    return Controller(step, reset).serve();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace lagrange::sdk
