#include "wiring/sampled_simulation.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <system_error>
#include <thread>

#include "model/reference.hpp"
#include "plant/scenario_plant.hpp"
#include "util/error.hpp"
#include "util/jobs.hpp"
#include "util/splitmix.hpp"
#include "wiring/inproc_runner.hpp"

namespace lagrange::wiring {

namespace {

using controller::SampledSimulation;

// The fine rate's cap, as a multiple of the configured rate.
constexpr int kMaxRefinement = 64;

using Loop = LoopOutcome;

struct StartState {
  std::string what;
  config::InitialState state;
  double error = 0.0;  ///< ||q(0) - q_d(0)|| [rad]
};

// The initial state, and kSeededStates more with the same ||q(0) - q_d(0)||
// in other directions (the rates as configured; the motors moved with the links).
std::vector<StartState> startsOf(const config::Scenario& s) {
  const model::Reference reference(s.reference);
  const Eigen::VectorXd qd0 = reference.evaluate(0.0, 0).q();
  std::vector<StartState> out = {{"the initial state", s.initial_state, (s.initial_state.q - qd0).norm()}};
  const plant::JointPhysics stops = plant::jointPhysicsFor(s);  // a seeded start stays inside the stops
  const double norm = out.front().error;
  if (!(norm > 0.0)) return out;
  util::SplitMix64Stream draws(1);
  for (int k = 1; k <= kSeededStates; ++k) {
    Eigen::VectorXd direction(s.dof());
    for (int i = 0; i < s.dof(); ++i) direction(i) = draws.gaussian();
    StartState start{"seeded state " + std::to_string(k), s.initial_state};
    start.state.q = qd0 + norm * direction.normalized();
    if (stops.lower.size() == s.dof())
      start.state.q = start.state.q.cwiseMax(stops.lower).cwiseMin(stops.upper);
    if (start.state.motor_q.size() == s.dof()) start.state.motor_q += start.state.q - s.initial_state.q;
    start.error = (start.state.q - qd0).norm();
    out.push_back(start);
  }
  return out;
}

// The scenario as configured, from `start`.
config::Scenario sampledScenario(const config::Scenario& s, const config::InitialState& start) {
  config::Scenario out = s;
  out.initial_state = start;
  if (s.mode == config::Mode::kRealtime) {  // every measurement a sample late
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s.dof());
    if (!out.sensors) {
      out.sensors = config::SensorsConfig{};
      out.sensors->position = {zero, zero, 0, {}};
    }
    ++out.sensors->position.delay;
    if (out.sensors->velocity) ++out.sensors->velocity->delay;
    if (s.flexible) {
      if (!out.sensors->motor) out.sensors->motor = config::JointSensorConfig{zero, zero, 0, {}};
      ++out.sensors->motor->delay;
    }
  }
  return out;
}

// The same loop at `rate`, exact sensors, one actuator update a period.
config::Scenario fineScenario(const config::Scenario& s, const config::InitialState& start, double rate) {
  config::Scenario out = s;
  out.initial_state = start;
  out.plant.publish_rate = rate;
  // The actuator as fast as this rate, or as configured when that is faster;
  // the physics step the scenario's, or less so that it divides the actuator's period.
  out.actuator.rate = rate * std::max(1.0, std::ceil(s.actuator.rate / rate - 1e-9));
  const double period = 1.0 / out.actuator.rate;
  out.plant.physics_step = period / std::ceil(period / s.plant.physics_step - 1e-9);
  out.sensors.reset();
  if (s.velocitySensor()) {  // a controller that reads the rates reads exact ones
    out.sensors = config::SensorsConfig{};
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s.dof());
    out.sensors->position = {zero, zero, 0, {}};
    out.sensors->velocity = config::JointSensorConfig{zero, zero, 0, {}};
  }
  return out;
}

// Whether two fine loops agree (the refinement's test).
bool agree(const Loop& a, const Loop& b, double tolerance, double period) {
  if (a.status != b.status) return false;
  if (a.time && b.time) return std::abs(*a.time - *b.time) <= 0.05 * *b.time + 2.0 * period;
  if (a.time || b.time) return false;
  return std::abs(a.error - b.error) <= 0.05 * b.error + 0.05 * tolerance;
}

std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g s", t);
  return buf;
}

// "12 %" for a fraction 0.12.
std::string percent(double fraction) {
  return std::to_string(static_cast<int>(std::lround(fraction * 100))) + " %";
}

// What the plant has that the paper's controller does not model, by which a
// loop keeps a steady offset at every rate: the likely cause named in an
// "offset" verdict.
std::string unmodelledEffects(const config::Scenario& s) {
  const plant::JointPhysics physics = plant::jointPhysicsFor(s);
  std::vector<std::string> causes;
  if (physics.damping.size() > 0 && physics.damping.cwiseAbs().maxCoeff() > 0.0)
    causes.push_back("joint damping");
  if (physics.friction.size() > 0 && physics.friction.cwiseAbs().maxCoeff() > 0.0)
    causes.push_back("joint friction");
  if ((physics.rotor_damping.size() > 0 && physics.rotor_damping.cwiseAbs().maxCoeff() > 0.0) ||
      (physics.rotor_friction.size() > 0 && physics.rotor_friction.cwiseAbs().maxCoeff() > 0.0))
    causes.push_back("rotor damping or friction");
  if (s.plant.payload) causes.push_back("a payload");
  if (s.plant.model_error) causes.push_back("model error");
  if (physics.lower.size() > 0) causes.push_back("the joints' stops");
  if (s.actuator.saturation) causes.push_back("torque limits below what the motion needs");
  if (causes.empty())
    return "none in the plant that the controller does not model: the loop may still be settling at the end "
           "of the run "
           "(a longer duration tells), or the law leaves this error on this reference";
  std::string out;
  for (size_t i = 0; i < causes.size(); ++i)
    out += (i == 0 ? "" : i + 1 == causes.size() ? " or " : ", ") + causes[i];
  return out + " in the plant, which the controller does not model";
}

// One start's verdict and its reason, before the probe about the reference:
// "suspect" is a start where sampling costs something (the sampled loop
// slower, or farther off, than the fine-rate one) -- "slow" or "unstable",
// which the probe (probeReference) decides.
std::pair<std::string, std::string> judge(const SampledSimulation::Start& st, double tolerance,
                                          double period) {
  if (st.fine_status != "completed")
    return {"not assessed", "the fine-rate loop itself was stopped (it diverged) from " + st.what};
  if (st.sampled_status != "completed")
    return {"diverges", "the sampled loop was stopped (it diverged) from " + st.what +
                            ", where the fine-rate loop ran to the end"};
  // Ended farther from the reference than it started, where the fine loop
  // ended close to it: a loop that runs away without the plant stopping it.
  if (st.sampled_error > st.initial_error && st.sampled_error > 10.0 * std::max(st.fine_error, tolerance)) {
    char why[256];
    std::snprintf(
        why, sizeof why,
        "from %s the sampled loop ended farther from the reference than it started (%.3g rad RMS over "
        "the last second, from %.3g rad), where the fine-rate loop ended at %.3g rad",
        st.what.c_str(), st.sampled_error, st.initial_error, st.fine_error);
    return {"diverges", why};
  }
  const double slack = SampledSimulation::kSlack;
  if (st.fine_time) {
    if (st.sampled_time && *st.sampled_time <= slack * *st.fine_time + 2.0 * period) return {"adequate", ""};
    std::string why = "from " + st.what + " the sampled loop ";
    if (st.sampled_time) {
      why += "converged at " + seconds(*st.sampled_time) + ", the fine-rate loop at " +
             seconds(*st.fine_time) + ": " + percent(*st.sampled_time / *st.fine_time - 1.0) +
             " later (the check allows " + percent(slack - 1.0) + " and two periods)";
    } else {
      char tail[160];
      std::snprintf(tail, sizeof tail, " (%.3g rad RMS over its last second)", st.sampled_error);
      why += "did not converge within the run" + std::string(tail) + ", the fine-rate loop converged at " +
             seconds(*st.fine_time);
    }
    return {"suspect", why};
  }
  const bool as_fine = st.sampled_error <= slack * st.fine_error + 0.25 * tolerance;
  if (as_fine) {
    if (st.sampled_time) return {"adequate", ""};
    // Neither loop reaches the tolerance, and the sampled one ends where the
    // fine one does: an offset sampling does not cause.
    char why[256];
    std::snprintf(
        why, sizeof why,
        "from %s neither the sampled loop (%.3g rad RMS over the last second) nor the fine-rate loop "
        "(%.3g rad) reached the tolerance",
        st.what.c_str(), st.sampled_error, st.fine_error);
    return {"offset", why};
  }
  char why[320];
  std::snprintf(
      why, sizeof why,
      "from %s the sampled loop ended %.3g rad off (RMS over the last second), more than %s above the "
      "fine-rate loop's %.3g rad",
      st.what.c_str(), st.sampled_error, percent(slack - 1.0).c_str(), st.fine_error);
  return {"suspect", why};
}

// The probe that tells "unstable about the reference" from "slow": the
// sampled loop as configured but without torque limits, started close to
// the reference (kProbeTolerances x the tolerance, or the starts' error if
// smaller, in a seeded direction, at the reference's rate). A loop stable
// about the reference ends near it; an unstable one grows (the limits lifted
// so that nothing but the loop itself bounds it).
constexpr double kProbeTolerances = 10.0;

config::Scenario probeScenario(const config::Scenario& s, double offset) {
  const model::Reference reference(s.reference);
  const model::ReferenceSample d = reference.evaluate(0.0, 1);
  util::SplitMix64Stream draws(2);
  Eigen::VectorXd direction(s.dof());
  for (int i = 0; i < s.dof(); ++i) direction(i) = draws.gaussian();
  config::InitialState start = s.initial_state;
  start.q = d.q() + offset * direction.normalized();
  start.qdot = d.qd();
  if (start.motor_q.size() == s.dof()) start.motor_q += start.q - s.initial_state.q;
  if (start.motor_qdot.size() == s.dof()) start.motor_qdot = start.qdot;
  config::Scenario out = sampledScenario(s, start);
  out.actuator.saturation.reset();
  return out;
}

// Whether the probe grew: stopped, or ended farther off than it started and
// well above where the fine-rate loop ends.
bool probeGrew(const Loop& probe, double offset, double fine_error, double tolerance) {
  return probe.status != "completed" ||
         (probe.error > 2.0 * offset && probe.error > 10.0 * std::max(fine_error, tolerance));
}

// What a loop costs, to start the longest first: its physics steps, and its
// ticks at about three physics steps' time each (a 2-joint arm's tick in
// process: sensors, controller, actuator, metrics).
double cost(const config::Scenario& s) {
  return static_cast<double>(s.lastTick() + 1) * (s.substepsPerTick() + 3.0);
}

// Runs each scenario's loop in process, up to `threads` at a time (the
// calling thread one of them), and returns what each did, in order. Each
// loop is a function of its scenario alone -- its own plant, ODE world,
// controller and metrics; the models and a free_motion reference's
// integration shared read-only -- so a result does not depend on the thread
// it ran on, nor on the order: the longest start first, so that the last to
// finish is a short one. A loop that throws counts as one that diverged.
// @throws SimulationStopped when `stop_requested` (asked every 100 ticks by
// each loop, from the threads) turns true: the loops running end, no verdict.
std::vector<Loop> simulateAll(const std::vector<config::Scenario>& scenarios, int threads,
                              bool (*stop_requested)() = nullptr) {
  std::vector<Loop> out(scenarios.size());
  std::vector<size_t> order(scenarios.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return cost(scenarios[a]) > cost(scenarios[b]); });
  std::atomic<size_t> next{0};
  std::atomic<bool> stopped{false};
  auto work = [&] {
    for (size_t k = next++; k < order.size() && !stopped; k = next++) {
      const size_t i = order[k];
      try {
        const InProcessOutcome o = simulateInProcess(scenarios[i], nullptr, nullptr, stop_requested);
        if (o.status == "interrupted") {
          stopped = true;
          return;
        }
        out[i] = {o.status == "completed" ? "completed" : "diverged", o.tracking.convergence_time,
                  o.tracking.rms_last_second};
      } catch (...) {  // the loop failed in a core: it diverged
        out[i] = {"diverged", std::nullopt, 0.0};
      }
    }
  };
  std::vector<std::thread> helpers;
  const size_t wanted = std::min(static_cast<size_t>(std::max(1, threads)), scenarios.size());
  for (size_t w = 1; w < wanted; ++w) {
    try {
      helpers.emplace_back(work);
    } catch (const std::system_error&) {  // no thread to be had: fewer do the same work
      break;
    }
  }
  work();
  for (std::thread& t : helpers) t.join();
  if (stopped) throw SimulationStopped();
  return out;
}

// The verdict from `starts` (the first the scenario's initial state): the
// fine rate confirmed by refinement on the first start up to `max_refinement`
// x the rate, then each start's sampled loop (the first one's given as
// `known_first` when already run) against its fine loop.
SampledSimulation check(const config::Scenario& s, const std::vector<StartState>& starts, int max_refinement,
                        int threads, const std::optional<Loop>& known_first,
                        bool (*stop_requested)() = nullptr) {
  const auto wall_start = std::chrono::steady_clock::now();
  SampledSimulation out;
  out.rate = s.plant.publish_rate;
  out.duration = s.duration;
  out.tolerance = s.metrics.tolerance;
  out.one_period_delay = s.mode == config::Mode::kRealtime;

  // A free_motion reference is integrated once for every loop below (model/reference.hpp).
  const model::Reference shared_reference(s.reference);

  // Every loop in one batch, so that the threads stay busy to the end: the
  // initial state's fine loop at F = 8 x the rate and at 2F (the
  // refinement's first test), the sampled loop from every start (the first
  // unless known), and the fine loop at F from the others -- run before F is
  // confirmed, and again at the confirmed F when that is finer.
  double fine = 8.0 * out.rate;
  std::vector<config::Scenario> runs = {fineScenario(s, starts[0].state, fine),
                                        fineScenario(s, starts[0].state, 2.0 * fine)};
  for (size_t i = known_first ? 1 : 0; i < starts.size(); ++i)
    runs.push_back(sampledScenario(s, starts[i].state));
  const size_t simulated_sampled = runs.size() - 2;
  for (size_t i = 1; i < starts.size(); ++i) runs.push_back(fineScenario(s, starts[i].state, fine));
  const std::vector<Loop> loops = simulateAll(runs, threads, stop_requested);

  // The fine rate, confirmed by refinement on the initial state: F and 2F
  // agree, else F doubles (its loop is the 2F one already run) up to the cap.
  Loop fine_initial = loops[0], finer = loops[1];
  bool refined = false;
  for (;;) {
    if (agree(fine_initial, finer, s.metrics.tolerance, 1.0 / fine)) {
      out.confirmed_at = 2.0 * fine;
      break;
    }
    if (2.0 * fine >= max_refinement * out.rate) break;
    fine *= 2.0;
    refined = true;
    fine_initial = finer;
    finer = simulateAll({fineScenario(s, starts[0].state, 2.0 * fine)}, threads, stop_requested).front();
  }
  out.fine_rate = fine;

  std::vector<Loop> sampled_loops;
  if (known_first) sampled_loops.push_back(*known_first);
  sampled_loops.insert(sampled_loops.end(), loops.begin() + 2,
                       loops.begin() + 2 + static_cast<long>(simulated_sampled));
  std::vector<Loop> fine_loops = {fine_initial};
  if (!refined) {
    fine_loops.insert(fine_loops.end(), loops.begin() + 2 + static_cast<long>(simulated_sampled),
                      loops.end());
  } else {  // F was refined: the other starts' fine loops at the F confirmed
    std::vector<config::Scenario> at_fine;
    for (size_t i = 1; i < starts.size(); ++i) at_fine.push_back(fineScenario(s, starts[i].state, fine));
    const std::vector<Loop> again = simulateAll(at_fine, threads, stop_requested);
    fine_loops.insert(fine_loops.end(), again.begin(), again.end());
  }

  const double period = 1.0 / out.rate;
  std::vector<std::string> whys;
  for (size_t i = 0; i < starts.size(); ++i) {
    SampledSimulation::Start st{
        starts[i].what,     sampled_loops[i].status, fine_loops[i].status, sampled_loops[i].time,
        fine_loops[i].time, sampled_loops[i].error,  fine_loops[i].error,  "",
        starts[i].error};
    const auto [verdict, why] = judge(st, s.metrics.tolerance, period);
    st.verdict = verdict;
    whys.push_back(why);
    out.starts.push_back(st);
  }

  // Where sampling costs something, is the sampled loop unstable about the
  // reference, or only slower? One more simulation decides, for every start.
  const bool suspect =
      std::any_of(out.starts.begin(), out.starts.end(),
                  [](const SampledSimulation::Start& st) { return st.verdict == "suspect"; });
  std::string probe_why;
  std::optional<Loop> probe;
  if (suspect) {
    const double offset = starts[0].error > 0.0 ? std::min(kProbeTolerances * out.tolerance, starts[0].error)
                                                : kProbeTolerances * out.tolerance;
    probe = simulateAll({probeScenario(s, offset)}, threads, stop_requested).front();
    const bool grew = probeGrew(*probe, offset, fine_initial.error, out.tolerance);
    char buf[512];
    char ended[96];
    if (probe->status != "completed")
      std::snprintf(ended, sizeof ended, "was stopped (it diverged)");
    else
      std::snprintf(ended, sizeof ended, "ended %.3g rad off (RMS over the last second)", probe->error);
    std::snprintf(buf, sizeof buf, "from %.3g rad off the reference the sampled loop%s %s%s", offset,
                  s.actuator.saturation ? " without its torque limits" : "", ended,
                  grew ? "" : ": stable about the reference");
    probe_why = buf;
    for (SampledSimulation::Start& st : out.starts)
      if (st.verdict == "suspect") st.verdict = grew ? "unstable" : "slow";
  }

  // The worst start decides.
  const std::vector<std::string> order = {"adequate", "offset",   "not assessed",
                                          "slow",     "unstable", "diverges"};
  auto rank = [&](const std::string& v) { return std::find(order.begin(), order.end(), v) - order.begin(); };
  out.verdict = "adequate";
  size_t worst = 0;
  for (size_t i = 0; i < out.starts.size(); ++i)
    if (rank(out.starts[i].verdict) > rank(out.verdict)) {
      out.verdict = out.starts[i].verdict;
      worst = i;
    }
  out.why = whys[worst];
  const auto count = [&](const std::string& verdict) {
    const auto n = std::count_if(out.starts.begin(), out.starts.end(),
                                 [&](const SampledSimulation::Start& st) { return st.verdict == verdict; });
    return n == static_cast<long>(out.starts.size())
               ? std::string(n > 1 ? "every start" : "its start")
               : std::to_string(n) + " of " + std::to_string(out.starts.size()) + " starts";
  };
  if (out.verdict == "adequate") {
    out.why = std::string(starts.size() > 1 ? "from every start the sampled loop" : "the sampled loop") +
              " converged within " + percent(SampledSimulation::kSlack - 1.0) +
              " of the fine-rate loop's time and two periods (or, where the fine-rate loop did not reach the "
              "tolerance, ended within as much of its error)";
  } else if (out.verdict == "offset") {
    char head[320];
    std::snprintf(
        head, sizeof head,
        "a steady offset the fine-rate loop at %g Hz shares, not sampling's doing: from %s neither "
        "loop reached the tolerance (%g rad), and the sampled loop ended within %s of the fine-rate "
        "loop's error; ",
        fine, count("offset").c_str(), out.tolerance, percent(SampledSimulation::kSlack - 1.0).c_str());
    out.why = head + out.why + "; likely cause: " + unmodelledEffects(s);
  } else if (out.verdict == "slow") {
    out.why = "slower than the fine-rate loop at " + std::to_string(static_cast<long long>(fine)) +
              " Hz: " + out.why + "; " + probe_why;
  } else if (out.verdict == "unstable") {
    const SampledSimulation::Start& w = out.starts[worst];
    char fine_end[96];
    std::snprintf(fine_end, sizeof fine_end,
                  ", where the fine-rate loop from the initial state ended %.3g rad off", fine_initial.error);
    std::string head = "about the reference: " + probe_why + fine_end;
    // Only saturation holds it off when, without the limits, the loop runs
    // away (stopped, or ten times farther off than the limited loop ends):
    // a loop that a nonlinearity of its own bounds without them is not.
    if (s.actuator.saturation && w.sampled_status == "completed" &&
        (probe->status != "completed" || probe->error > 10.0 * w.sampled_error)) {
      char held[256];
      std::snprintf(held, sizeof held,
                    "; held off only by saturation: with the torque limits (actuator.saturation) the loop "
                    "stays bounded, %.3g rad off from %s",
                    w.sampled_error, w.what.c_str());
      head += held;
    }
    out.why = head + "; " + out.why;
  }
  if (!out.confirmed_at) {
    // adequate and offset compare with the fine-rate loop, which then stands for nothing.
    if (out.verdict == "adequate" || out.verdict == "offset") out.verdict = "not assessed";
    out.why = "no fine rate up to " + std::to_string(max_refinement) +
              " x the configured one agreed with the next finer, so no loop stands for continuous time; " +
              out.why;
  }
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return out;
}

SampledSimulation notAssessedExternal(const config::Scenario& s) {
  SampledSimulation out;
  out.rate = s.plant.publish_rate;
  out.duration = s.duration;
  out.tolerance = s.metrics.tolerance;
  out.one_period_delay = s.mode == config::Mode::kRealtime;
  out.verdict = "not assessed";
  out.why = s.plant.external()
                ? "an external plant does not run in process, where the check simulates the loop (the "
                  "linearised estimate uses the robot section's model)"
                : "an external controller does not run in process, where the check simulates the loop";
  return out;
}

}  // namespace

SampledSimulation simulateSampledData(const config::Scenario& s, int jobs,
                                      const std::optional<LoopOutcome>& initial_run) {
  if (s.controller.type == "external" || s.plant.external()) return notAssessedExternal(s);
  const int threads = util::jobsOrCores(jobs);
  return check(s, startsOf(s), kMaxRefinement, threads,
               s.mode == config::Mode::kRealtime ? std::nullopt : initial_run);
}

SampledSimulation judgeRun(const config::Scenario& s, const LoopOutcome& run, bool (*stop_requested)()) {
  if (s.controller.type == "external" || s.plant.external()) return notAssessedExternal(s);
  config::Scenario in_process = s;
  in_process.mode = config::Mode::kInproc;
  const std::vector<StartState> start = {startsOf(in_process).front()};
  return check(in_process, start, kRunRefinement, 1, run, stop_requested);
}

}  // namespace lagrange::wiring
