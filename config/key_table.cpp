/// @file
/// The table of every scenario key (config/key_table.hpp).
#include "config/key_table.hpp"

#include <iterator>
#include <map>
#include <stdexcept>

namespace lagrange::config {

namespace keyrow {

KeyInfo row(std::string key, std::string type, std::string default_text, std::string meaning) {
  return {std::move(key), std::move(type), std::move(default_text), std::move(meaning), std::nullopt, "", ""};
}
KeyInfo row(std::string key, std::string type, std::string default_text, std::string meaning,
            KeyRange range) {
  KeyInfo k = row(std::move(key), std::move(type), std::move(default_text), std::move(meaning));
  k.range = std::move(range);
  return k;
}
// A key of a list item or map entry, or a registered controller's gain,
// described in the row of `described_in`.
KeyInfo inside(std::string key, std::string described_in, KeyRange range) {
  return {std::move(key), "", "", "", std::move(range), "", std::move(described_in)};
}
KeyInfo only(std::string variant, KeyInfo k) {
  k.variant = std::move(variant);
  return k;
}

// Ranges several keys share. Angles may be multi-turn; rates and gains stay
// far below where their products (gain x error x rate) leave double's range.
KeyRange angle() { return {-1e6, 1e6, false, "rad", ""}; }
KeyRange rate() { return {-1e4, 1e4, false, "rad/s", "about 95 000 rpm"}; }
KeyRange gain() {
  return {0.0, 1e12, true, "",
          "gains beyond 1e12 overflow or swamp the physics; the paper's constructive gains for long chains "
          "(check-gains --suggest) reach 1e125 and are evaluated there, not run"};
}
KeyRange largeState() { return {-1e15, 1e15, false, "", ""}; }  // filter and chain states
}  // namespace keyrow

namespace {
using namespace keyrow;

KeyRange probability() { return {0.0, 1.0, false, "", ""}; }
KeyRange faultDelay() { return {0.0, 60.0, false, "s", "a datagram held longer is lost, not late"}; }
KeyRange noise() { return {0.0, 1e3, false, "", ""}; }
KeyRange counts() { return {0.0, 1e12, false, "", ""}; }
KeyRange sensorDelay() { return {0.0, 1e5, false, "samples", "each sensor keeps that many readings"}; }
KeyRange seed() { return {0.0, 1e9, false, "", ""}; }

// What the run is: its name, length and wiring.
std::vector<KeyInfo> runKeys() {
  return {
      row("extends", "path", "none",
          "another scenario file (relative to this one's folder) read first: this file's keys are merged "
          "over it (maps key by key, lists and numbers replaced whole; a section whose `type` changes, "
          "e.g. `controller`, replaced whole), then `--set` applies. It may "
          "extend a third; a cycle is refused. "
          "Relative `robot.urdf.file`, `controller.working_directory` and the program of "
          "`controller.command` (a path) of a base file stay relative to its own folder. An error about a "
          "key in a merged scenario names the line of the file that wrote it (\"(line 5 of base.yaml, which "
          "this file extends)\"), or, for a key none wrote (one missing), the files. The resolved scenario "
          "has no `extends`; "
          "`--set extends` is refused"),
      row("name", "string", "required", "scenario name, shown in outputs"),
      row("description", "string", "`\"\"`", "free text"),
      row("duration", "number > 0", "required",
          "simulated time [s]; must be a whole number of publish periods.",
          {0.0, 1e9, true, "s", "the samples, physics steps, memory and log it asks for are bounded too"}),
      row("mode", "string", "`lockstep`",
          "`lockstep`: processes over LCM, sim time advances when every process has answered the tick "
          "(deterministic, faster than real time); `realtime`: processes over LCM, each on its own "
          "fixed-rate loop at `plant.publish_rate` (sim time = wall time); `inproc`: the same cores "
          "called in one process, no LCM (bit-identical to lockstep). `lagrange run --mode` overrides "
          "it"),
  };
}

// The arm and where it starts.
std::vector<KeyInfo> armKeys() {
  return {
      row("robot.preset", "string", "—",
          "`pelican`: the 2-DOF arm of Kelly, Santibáñez and Loría (give exactly one of `preset`, "
          "`links` or `urdf`)"),
      row("robot.links", "list of maps", "—",
          "base to tip, each `{length, com, mass, inertia}`: joint-to-joint length [m] > 0, "
          "joint-to-centre-of-mass distance [m] ≥ 0, mass [kg] > 0, moment of inertia about the centre "
          "of mass [kg m²] > 0."),
      inside("robot.links[i].com", "robot.links", {0.0, 1e3, false, "m", ""}),
      inside("robot.links[i].inertia", "robot.links", {1e-12, 1e6, false, "kg m^2", ""}),
      inside("robot.links[i].length", "robot.links", {1e-4, 1e3, false, "m", ""}),
      inside("robot.links[i].mass", "robot.links", {1e-6, 1e6, false, "kg", ""}),
      row("robot.urdf.file", "string", "—",
          "a serial arm from a URDF file instead of `preset` or `links` (give exactly one): the file, "
          "relative to the scenario file's folder. The chain from `base_link` to `tip_link` is the "
          "arm: revolute and continuous joints are its joints (in order, named as in the URDF), fixed "
          "joints stay rigid, and every branch off the chain (the Panda's fingers) is held at its zero "
          "position with its mass lumped into the link it hangs from. Gravity acts along the URDF "
          "world's −z, base_link's frame is the world (a fixed base). URDF joint limits and `<dynamics "
          "damping friction>` are not in the controllers' model (lossless, eq. (1)); the plant applies "
          "them only when asked (`plant.urdf_dynamics`, `plant.joint_limits`, `actuator.saturation: "
          "urdf`), and `lagrange run` lists them at start. Refused before anything starts, with the file and "
          "the link or joint named: a "
          "file that cannot be read or is not URDF (urdfdom's words quoted), an unknown link (the "
          "known ones listed), a tip not below the base, a prismatic, planar or floating joint on the "
          "chain, a negative mass, a mass of 0 with a non-zero tensor (0 with a zero tensor is a "
          "massless frame, accepted), an inertia tensor that is not positive definite or whose "
          "principal moments violate the triangle inequality, a joint that moves no mass. Shipped: "
          "`robots/panda.urdf`, `robots/ur5_robot.urdf`, `robots/double_pendulum.urdf` "
          "(robots/README.md)"),
      row("robot.urdf.base_link", "string", "required with `urdf`", "the fixed link the chain starts from"),
      row("robot.urdf.tip_link", "string", "required with `urdf`", "the last link of the chain"),
      row("robot.urdf.xml", "string", "the file's text",
          "the URDF document itself; when given it is used and `file` is not read. "
          "`config.resolved.yaml` and the SCENARIO message carry it, so a run's log replays without "
          "the file"),
      row("robot.gravity", "number ≥ 0", "`9.81`", "g [m/s²], downwards in the plane of motion.",
          {0.0, 1e3, false, "m/s^2", "about 100 g"}),
      row("robot.flexible.stiffness", "vector or scalar > 0", "— (section optional)",
          "K [N m/rad]: elastic joints (eq. (41)), each joint driven through a torsional spring by a "
          "base-mounted rotor.",
          {0.0, 1e12, true, "N m/rad", ""}),
      row("robot.flexible.rotor_inertia", "vector or scalar > 0", "required with `flexible`",
          "J [kg m²], each rotor's inertia about its axis (reflected to the joint).",
          {1e-12, 1e6, false, "kg m^2", ""}),
      row("robot.flexible.rate_sensor", "`true` / `false`", "`false`",
          "the motors have rate sensors: PLANT_MOTOR carries q2'"),
      row("initial_state.q", "vector (list)", "required",
          "initial joint angles [rad]; for a planar chain relative angles, joint 1 from the downward "
          "vertical, counter-clockwise positive; for a URDF arm the URDF's joint angles, in chain "
          "order (positive by the right-hand rule about each `<axis>`); any value (multi-turn).",
          angle()),
      row("initial_state.qdot", "vector (list)", "zeros", "initial joint rates [rad/s].", rate()),
      row("initial_state.motor_q", "vector (list)", "q + K⁻¹ g(q)",
          "flexible joints only: initial motor angles q2 [rad]; the default twists each spring just "
          "enough to hold the links at rest against gravity.",
          angle()),
      row("initial_state.motor_qdot", "vector (list)", "`initial_state.qdot`",
          "flexible joints only: initial motor rates [rad/s].", rate()),
  };
}

// What the arm tracks.
std::vector<KeyInfo> referenceKeys() {
  return {
      row("reference.type", "string", "required",
          "`sine`: q_d,i = b_i + c_i sin(w_i t + p_i); `smooth_sine`: the same times (1 − exp(−alpha_i "
          "t³)); `free_motion`: the unforced motion D(q)q'' + C(q,q')q' + g(q) = 0 of the configured "
          "robot (Assumption 2 of Theorems 5 and 6), integrated by RK4 with a 0.1 ms step over the run "
          "and a second more (derivatives up to q_d'' only). Sinusoids are not free motions: the "
          "cascaded controller then warns that the theorems' hypothesis does not hold"),
      only("free_motion",
           row("reference.initial_q", "vector (list)", "required",
               "`free_motion`: the initial angles of the free motion [rad] (no other reference key applies).",
               angle())),
      only("free_motion", row("reference.initial_qdot", "vector (list)", "zeros",
                              "`free_motion`: the initial rates of the free motion [rad/s].", rate())),
      only("sine", row("reference.offset", "vector or scalar", "required", "b [rad].", angle())),
      only("sine",
           row("reference.amplitude", "vector or scalar", "required",
               "c [rad]; 0 on every joint makes q_d constant (= offset), the reference of the `set_point` "
               "controller.",
               angle())),
      only("sine",
           row("reference.frequency", "vector or scalar ≥ 0", "required", "w [rad/s].",
               {0.0, 1e4, false, "rad/s", "1.6 kHz, above the Nyquist frequency of any arm's controller"})),
      only("sine", row("reference.phase", "vector or scalar", "zeros", "p [rad].", angle())),
      only("sine", row("reference.alpha", "vector or scalar > 0", "required for `smooth_sine`",
                       "start-up rate [1/s³]; not allowed for `sine`.",
                       {1e-6, 1e6, false, "1/s^3", "a start-up between 0.03 s and 300 s"})),
  };
}

// The simulation and the actuator chain.
std::vector<KeyInfo> plantAndActuatorKeys() {
  return {
      row("plant.type", "string", "`simulated`",
          "`simulated`: the plant process simulates the arm with `plant.engine` and the keys below; "
          "`external`: a program from outside the project takes the plant's place over LCM -- a "
          "simulator of your own or a bridge to a real arm (keys `command`, `working_directory`, "
          "`publish_rate`; docs/external_programs.md, docs/hardware.md). The other `plant` keys and a "
          "`sensors` section are the simulated plant's and refused beside it; it needs rigid joints, "
          "`mode` lockstep or realtime and one torque per period (the actuator's rate = `publish_rate`)."),
      only("external_plant",
           row("plant.command", "list of strings", "required for `external`",
               "the external plant's command line (argv, no shell): the launcher starts it in the plant's "
               "place, writes its output to `plant.log` and ends the run when it exits, as it does the "
               "built-in plant's. A name on PATH or a path relative to the scenario file's folder; a "
               "missing one is refused before anything starts. Its environment is an external "
               "controller's (`LAGRANGE_LCM_URL`, `LAGRANGE_RUN_ID`, `LAGRANGE_KEY_FILE`, "
               "`LAGRANGE_CONFIG`, `LAGRANGE_CONFIG_JSON`, `LAGRANGE_JOINTS`, `LAGRANGE_MODE`, "
               "`LAGRANGE_CLOCK_OFFSET_US`); `lagrange replay LOG --component plant -- COMMAND` gives "
               "the same")),
      only("external_plant", row("plant.working_directory", "path", "the scenario file's folder",
                                 "where the external plant starts (relative to the scenario file's folder)")),
      row("plant.engine", "string", "`ode`",
          "the physics engine that simulates the arm: `ode` (the Open Dynamics Engine, maximal "
          "coordinates: the design's engine, and the golden logs') or `mujoco` (MuJoCo 2.2, generalized "
          "coordinates, the model generated from the arm's parameters or its URDF: "
          "docs/extending.md, \"Physics engines\"), or one a program registers. Every wiring and "
          "replay builds the engine the scenario names. Written to config.resolved.yaml only when not "
          "`ode`."),
      row("plant.mujoco_integrator", "string", "`rk4`",
          "with `plant.engine: mujoco` only: MuJoCo's integrator, `rk4` (4th-order Runge-Kutta: the "
          "springs of flexible joints and the damping explicit), `implicit` (damping implicit, stable "
          "for any damping and step) or `euler` (semi-implicit Euler, damping implicit). Refused beside "
          "another engine."),
      row("plant.physics_step", "number > 0", "`1.0e-4`",
          "the engine's step [s]; `1/publish_rate` must be a whole multiple of it.",
          {1e-7, 1.0, false, "s",
           "a step below 0.1 us only adds rounding; the steps a run asks for are bounded too"}),
      row("plant.publish_rate", "number > 0", "`1000`",
          "position samples per second [Hz]; one lockstep tick per sample, the controller runs at this "
          "rate. Whether the sampled implementation is adequate at this rate is `check-gains`' "
          "sampled-data check (docs/sampled_data.md).",
          {0.1, 1e5, false, "Hz", ""}),
      row("plant.max_rate", "number > 0", "none",
          "a limit on any body's angular rate [rad/s]: the plant stops the run when it is crossed "
          "(exit 1, the limit named, the log kept). Unset, nothing but a failing simulation stops a "
          "run: a non-finite state, or a body turning by more than π/2 per physics step (π/(2 "
          "`physics_step`) rad/s, 62 832 rad/s at 2.5e-5 s), past which ODE cannot integrate the "
          "motion (the same limit on MuJoCo, which also stops a run at its own alarm: an angle, rate or "
          "acceleration not finite or beyond 1e10). There is deliberately no default limit: the paper's "
          "results are global, and "
          "converging runs from large errors pass through fast motion. ODE bleeds speed from fast "
          "links long before that limit (about 14 % in 10 ms at 0.06 rad per step): fast motion wants "
          "a small `physics_step`.",
          {0.0, 1e9, true, "rad/s", ""}),
      row("plant.joint_damping", "vector or scalar ≥ 0", "none",
          "viscous damping of the arm's joints, D_i [N m s/rad]: a torque −D_i q̇_i in the plant (on ODE a "
          "motor solved with the step, so stable for any D; on MuJoCo the joint's `damping`, explicit "
          "under `plant.mujoco_integrator: rk4`), which the controllers' lossless model "
          "(eq. (1)) does not know. Overrides the URDF's `<dynamics damping>` under `plant.urdf_dynamics`. "
          "PLANT_TRUTH's energies then fall by what the damping and the friction take: E(t) − E(0) = "
          "∫ τᵀq̇ − ∫ (D q̇² + F |q̇|) dt without stops (a test holds it on a run's log).",
          {0.0, 1e6, false, "N m s/rad", ""}),
      row("plant.joint_friction", "vector or scalar ≥ 0", "none",
          "Coulomb friction of the arm's joints, F_i [N m]: a torque of at most F_i against the joint's "
          "motion, and a joint at rest stays at rest while the rest of its torque is below F_i "
          "(stiction; on ODE a motor with force limit F_i aiming at zero rate, not a sign() term; on "
          "MuJoCo the joint's `frictionloss`, a soft constraint as stiff as MuJoCo advises: a resting link "
          "creeps about 4e-7 rad in 0.1 s under 0.9 F_i). "
          "Overrides the URDF's `<dynamics friction>` under `plant.urdf_dynamics`.",
          {0.0, 1e6, false, "N m", ""}),
      row("plant.urdf_dynamics", "`true` / `false`", "`false`",
          "a URDF arm: apply each joint's `<dynamics damping friction>` in the plant (where "
          "`plant.joint_damping` / `joint_friction` do not say otherwise). Off by default, so that the "
          "shipped Panda and UR5 results stand; refused for an arm without a URDF, or a URDF whose "
          "values are negative."),
      row("plant.rotor_damping", "vector or scalar ≥ 0", "none",
          "an arm with `robot.flexible`: viscous damping of the rotors' bearings [N m s/rad], as "
          "`joint_damping`; refused without rotors.",
          {0.0, 1e6, false, "N m s/rad", ""}),
      row("plant.rotor_friction", "vector or scalar ≥ 0", "none",
          "an arm with `robot.flexible`: Coulomb friction of the rotors' bearings [N m], as "
          "`joint_friction`; refused without rotors.",
          {0.0, 1e6, false, "N m", ""}),
      row("plant.joint_limits", "`true` / `false`", "`false`",
          "a URDF arm: each revolute joint's `<limit lower upper>` is a hard stop in the plant "
          "(inelastic; ODE's hinge stops, placed relative to the joint's turn so that limits beyond ±π "
          "hold too; on MuJoCo the joint's `range`, a soft constraint that gives about 1e-3 rad when a "
          "light link hits it at 8 rad/s). The controllers do not know them. Refused for an arm without a "
          "URDF, or when "
          "`initial_state.q` starts outside them."),
      row("plant.payload.mass", "number ≥ 0", "none",
          "a point mass [kg] at the last link that the controllers do not know of (they keep the "
          "nominal arm): merged into the plant's last body by the parallel-axis theorem. The section "
          "`plant.payload` is absent by default.",
          {0.0, 1e4, false, "kg", ""}),
      row("plant.payload.com", "number (planar chain) or 3 numbers (URDF arm)", "0",
          "where the payload sits [m]: on the planar chain's last link, its distance from the last "
          "joint along the link; on a URDF arm, a point in `tip_link`'s frame.",
          {-100.0, 100.0, false, "m", "a payload more than 100 m from its link is a typo"}),
      row("plant.model_error.mass", "number in [0, 0.9]", "0",
          "seeded relative error of every link's mass in the plant, which the controllers do not see "
          "(they keep the nominal URDF or chain): mass_i (1 + size u_i), u_i uniform in [−1, 1] "
          "(model/plant_perturbation.hpp). summary.json `plant.links` lists each link's nominal and "
          "actual values. The section `plant.model_error` is absent by default.",
          {0.0, 0.9, false, "", "a size of 1 could make a mass 0"}),
      row("plant.model_error.inertia", "number in [0, 0.9]", "0",
          "relative error of every link's inertia tensor (scaled as a whole), as `mass`.",
          {0.0, 0.9, false, "", "a size of 1 could make an inertia 0"}),
      row("plant.model_error.com", "number in [0, 0.9]", "0",
          "relative error of every link's centre-of-mass distance from its joint, as `mass`.",
          {0.0, 0.9, false, "", "a size of 1 could put a centre of mass on its joint"}),
      row("plant.model_error.seed", "integer ≥ 0", "`1`",
          "seeds the draws (SplitMix64; per link, in the order mass, inertia, com): the same seed, "
          "the same plant.",
          {0.0, 1e9, false, "", ""}),
      row("actuator.order", "integer 0–4", "`0`",
          "m, the order of the actuator's integrator chain (eq. (39)): 0, the torque passes through "
          "(controller `theorem1`); m ≥ 1, u drives xi_m' and xi_1 is the torque (controller "
          "`cascaded`). The chain is integrated exactly for u held over each period; the plant applies "
          "xi_1 as it is at each actuator update (`actuator.rate`), held in between.",
          {0.0, 4.0, false, "", ""}),
      row("actuator.rate", "number > 0 [Hz]", "`plant.publish_rate`",
          "how often the actuator updates the torque: a whole multiple S of `plant.publish_rate` whose "
          "period is a whole multiple of `plant.physics_step`. The plant applies xi_1 at each update, "
          "held until the next (S updates per period, carried in one ACTUATOR_STATE).",
          {0.1, 1e6, false, "Hz", ""}),
      row("actuator.initial_state", "list of m rows of n numbers (or one number per row)", "zeros",
          "xi_1(0) … xi_m(0).", largeState()),
      row("actuator.saturation", "vector or scalar > 0, or `urdf`", "none",
          "per-joint torque limit [N m]: the actuator clips each joint's torque to ±limit; absent: no "
          "limit. `urdf`: each joint's `<limit effort>` of the arm's URDF (refused for an arm without "
          "one, or a joint without an effort); config.resolved.yaml then holds the numbers.",
          {0.0, 1e12, true, "N m", ""}),
  };
}

// The controller: the paper's, the baselines' gains, an external one.
std::vector<KeyInfo> controllerKeys() {
  return {
      row("controller.type", "string", "required",
          "`theorem1`: Theorem 4, eq. (13), for `actuator.order` 0; `cascaded`: Theorem 5, eqs. (48), (66), "
          "for "
          "`actuator.order` ≥ 1 (its stage 0 takes `kp`, `kd`, `a`, `b`, `initial_filter_state` "
          "below); `flexible`: Corollary 3, eq. (83), for an arm with `robot.flexible` and "
          "`actuator.order` 0 (the cascade with m = 2 on xi_1 = K q2, xi_2 = K q2'; stages below); "
          "`pd_plus_differenced`: PD+ with the velocity replaced by the backward difference of the "
          "positions, a baseline (docs/baselines.md; keys `kp`, `kd`, `actuator.order` 0); "
          "`set_point`: Kelly's set-point controller, a baseline for a constant q_d (a `sine` "
          "reference with amplitude 0; keys `kp`, `kd`, `a`, `b`); `nicosia_tomei`: PD+ on Nicosia and "
          "Tomei's velocity observer, a baseline (keys `kp`, `kd`, `lp`, `ld`); `berghuis_nijmeijer`: "
          "Berghuis and Nijmeijer's controller–observer, a baseline (keys `kp`, `kd`, `lambda`, `lp`, "
          "`ld`); `pd_plus`: Paden and Panja's PD+ on the measured velocity, a baseline (keys `kp`, "
          "`kd`; needs `sensors.velocity`); `slotine_li`: Slotine and Li's controller on the measured "
          "velocity, a baseline (keys `lambda`, `kd`; needs `sensors.velocity`); `external`: a program "
          "from outside the project in the controller's place, over LCM (keys `command`, "
          "`working_directory`; [external_programs.md](external_programs.md)); or a type "
          "registered by `controller::registerControllerKind` in programs built with it "
          "(docs/extending.md, \"Adding a controller\"): its own per-joint keys instead of the ones "
          "below, `actuator.order` 0."),
      only("external",
           row("controller.command", "list of strings", "required for `external`",
               "the external controller's command line (argv, no shell): the launcher starts it in the "
               "controller's place, supervises it (`supervision.restart` applies) and writes its output to "
               "`controller.log`. The program is a name on PATH or a path, relative to the scenario file's "
               "folder; a missing one is refused before anything starts. It finds the run in its "
               "environment: `LAGRANGE_LCM_URL`, `LAGRANGE_RUN_ID`, `LAGRANGE_KEY_FILE` (the run's key), "
               "`LAGRANGE_CONFIG` and `LAGRANGE_CONFIG_JSON` (the resolved scenario as YAML and as JSON), "
               "`LAGRANGE_JOINTS`, `LAGRANGE_MODE`, `LAGRANGE_CLOCK_OFFSET_US` "
               "(docs/external_programs.md); "
               "`lagrange replay LOG -- COMMAND` gives the same")),
      only("external", row("controller.working_directory", "path", "the scenario file's folder",
                           "where the external controller starts (relative to the scenario file's folder)")),
  };
}

// How the run is judged and carried out.
std::vector<KeyInfo> judgementKeys() {
  return {
      row("metrics.tolerance", "number > 0", "`1.0e-3`", "tolerance on ‖q̃‖ [rad] for the convergence time.",
          {0.0, 1e6, true, "rad", ""}),
      row("metrics.convergence_deadline", "number > 0", "`5.0`",
          "the scenario's stated metric: converged by this time [s] (`tracking.met`).",
          {0.0, 1e9, true, "s", ""}),
      row("metrics.xi_tolerance", "number > 0", "`1.0e-2`",
          "cascaded controller: tolerance on every chain error ‖xi_i − xi_i*‖ [N m / s^(i−1)]; each "
          "must also converge by the deadline for `tracking.met`.",
          {0.0, 1e15, true, "", ""}),
      row("lockstep.retransmit_timeout", "number > 0", "`0.05`",
          "wall time [s] after which the plant re-sends a position nobody answered.",
          {1e-3, 3600.0, false, "s",
           "faster re-sends flood the bus and the log, where each is recorded, before an answer can come "
           "back"}),
      row("lockstep.stall_timeout", "number > 0", "`10`",
          "wall time [s] the run may wait without progress: in lockstep for a tick's answer "
          "(ACTUATOR_STATE, and so the controller's CONTROL_COMMAND) or for the logger; at the start — "
          "every process reporting, the first tick answered, in either mode — three times as long "
          "(processes load, check their gains, start a JVM), and so does a wait after the plant "
          "receives SIGCONT (a restart by `supervision.restart`, or the plant resumed after a "
          "SIGSTOP). Past it the plant stops the run (exit 1) naming whom it waited for, on which "
          "channel, and what was seen instead, e.g. `plant: stalled at tick 0: no ACTUATOR_STATE "
          "answered it in 30 s; awaited: the controller -- no valid CONTROL_COMMAND for tick 0 reached "
          "the actuator (it accepted 0 CONTROL_COMMAND and rejected 214 (214 unauthenticated))`, "
          "instead of waiting forever.",
          {0.1, 86400.0, false, "s",
           "shorter would stop runs that are only slow (a loaded machine, a sanitizer build); a day is past "
           "any run's pause"}),
      row("lockstep.logger_window", "integer ≥ 1", "`20`",
          "ticks the plant may run ahead of the logger (flow control, so the log misses nothing: what "
          "is in flight must fit the logger's UDP receive buffer; the logger asks for 4 MB, which the "
          "kernel caps at `net.core.rmem_max`, 208 kB on a stock Debian, where each small datagram "
          "costs about 1 kB of it).",
          {1.0, 1e4, false, "ticks", ""}),
      row("lockstep.logger_nice", "integer 0–19", "`5`",
          "the logger's nice value in a lockstep run (at least this; the logger sets it before its "
          "threads start; summary.json `timing.logger_nice` shows what it ran at). The logger is off "
          "the tick's critical path -- the plant waits for it only `logger_window` ticks ahead -- so "
          "where four processes share fewer cores it should give way to the three that are on it: on "
          "2 cores, 5 gave 8 % more ticks/s than 0 (median of 8 alternating pairs, 4 to 24 %; "
          "docs/performance.md). 0 runs it as the others, for a machine loaded by other work, where a "
          "niced logger falls behind that work and holds the plant back.",
          {0.0, 19.0, false, "", ""}),
      row("realtime.max_torque_age", "integer ≥ 1", "`2`",
          "realtime: a torque is fresh while the position it answers is at most this many periods old; "
          "the plant normally applies the answer to the previous tick (age 1).",
          {1.0, 1e6, false, "periods", ""}),
      row("realtime.stale_torque", "string", "`hold`",
          "realtime: what the plant does when no fresh torque is there: `hold` applies the newest "
          "torque received (late, its final step held flat) while it is at most `hold_periods` periods "
          "older than `max_torque_age` allows, then applies zero; `zero` applies zero at once. Both "
          "are counted (`messages.stale.plant`). `hold` is the default because a scheduling hiccup of "
          "a few ms on a shared machine would otherwise drop the arm under gravity"),
      row("realtime.hold_periods", "integer ≥ 0", "`20`",
          "realtime, policy `hold`: how many periods past `max_torque_age` a torque is still held (20 "
          "periods: the limit robot interfaces such as Franka's allow before they stop).",
          {0.0, 1e6, false, "periods", ""}),
      row("realtime.priority", "integer 0–99", "`50`",
          "realtime: SCHED_FIFO priority of the plant, controller, actuator and logger (memory locked "
          "with mlockall, the stack and a heap reserve faulted in before the loops); 0 for the normal "
          "scheduler. Without root or CAP_SYS_NICE the processes warn and "
          "run under the normal scheduler; `timing.loops.NAME.scheduler` says which. An external "
          "controller gets SCHED_FIFO one priority below this from the launcher, set before its program "
          "starts (FIFO from its first instruction, its start-up must not hold off the built-in loops; its "
          "log says what was set; memory locking is the program's own to ask for).",
          {0.0, 99.0, false, "", ""}),
      row("realtime.cpus.PROCESS", "list of CPU numbers 0–1023", "none: where the scheduler puts it",
          "realtime: the CPUs the process PROCESS (`plant`, `controller`, `actuator` or `logger`) may run "
          "on (`sched_setaffinity`, before its loop starts), e.g. `realtime: {cpus: {plant: [2], "
          "controller: [3], actuator: [3], logger: [0]}}` to keep the logger off the loops' cores on a "
          "machine with cores to spare (docs/engines_and_arms.md, \"A real machine\"). A CPU the machine "
          "does "
          "not have stops the process at start (exit 2, naming the key and the machine's CPUs); "
          "`timing.loops.NAME.scheduler` shows the CPUs a loop ran on (`fifo:50 cpus 3`). An external "
          "controller is pinned by the launcher before its program starts.",
          {0.0, 1023.0, false, "", ""}),
      row("realtime.max_input_age", "number > 0", "`0.005`",
          "realtime: the controller never acts on a position older than this [s], the actuator never "
          "on a command older than this; such inputs are skipped and counted.",
          {1e-6, 3600.0, false, "s", ""}),
      row("supervision.restart", "list of `controller`, `actuator`", "`[]`",
          "processes the launcher restarts when they die (crash, signal): a fresh process with a fresh "
          "state takes over mid-run. In realtime the plant's stale-torque policy holds the arm "
          "meanwhile; a restarted Theorem 4 (`theorem1`) controller starts its filter afresh and brings the "
          "arm "
          "back from wherever the gap left it. That it does is what the tests show for the shipped "
          "configs; the paper's *global* result is about the continuous-time loop, and the sampled 1 "
          "kHz loop is only covered locally, by the linearised sampled-data check, and from three "
          "starts by the simulated one (`check-gains`; docs/sampled_data.md), so a gap that throws the arm "
          "far enough can leave it outside what "
          "the implementation recovers from. In lockstep the plant waits, re-sending its position, and "
          "the actuator re-sends its last state (which a fresh cascaded controller needs) until the "
          "new controller answers; the launcher sends the plant a SIGCONT when it restarts a process, "
          "and the plant's wait then gets the start-up allowance (three times "
          "`lockstep.stall_timeout`), since the fresh process loads and checks its gains first (a "
          "SIGSTOP/SIGCONT of the plant gets the same). The plant (the simulated arm) and the logger "
          "(the log) cannot be restarted"),
      row("supervision.max_restarts", "integer ≥ 0", "`3`",
          "restarts per process; its next death stops the run (exit 1, the process and how it died "
          "named).",
          {0.0, 1000.0, false, "", ""}),
      row("supervision.slow_answer", "number > 0", "`1`",
          "wall time [s] past which an answer is slow: the controller's CONTROL_COMMAND to the plant's "
          "PLANT_POSITION of the same tick, the actuator's ACTUATOR_STATE to that command, and in lockstep "
          "the plant's (built-in or from outside) next PLANT_POSITION to that state, timed by the "
          "logger as it hears them (LCM modes; a program from outside reports nothing itself). A wait "
          "past it is said on the terminal while it lasts (until the plant's last tick), e.g. `lagrange run: "
          "the controller (python3 "
          "my_controller.py) has not answered tick 510 for 1.0 s (supervision.slow_answer = 1 s)`, "
          "then at most every 10 s; `summary.json` `answers` has each one's median and worst answer "
          "and how many were slow, and the run's verdict warns of them. Only said: "
          "`lockstep.stall_timeout` is what stops a run (and a plant not heard for 4 x "
          "`lockstep.stall_timeout` is named by the logger, which then stops it).",
          {0.001, 86400.0, false, "s",
           "below a millisecond every answer would be slow; a day is past any run's pause"}),
  };
}

// What the wiring and the sensors do to the signals.
std::vector<KeyInfo> faultAndSensorKeys() {
  return {
      row("faults.seed", "integer ≥ 0", "`1`",
          "seed of the fault injection; each process draws its own stream from it and its name, the "
          "same in every run with this seed.",
          seed()),
      row("faults.channels.NAME", "map", "none",
          "faults injected on the sending side of channel NAME (`PLANT_POSITION`, `PLANT_TRUTH`, "
          "`PLANT_MOTOR`, `PLANT_RATE`, `CONTROL_COMMAND`, `ACTUATOR_STATE`, `STATUS`, `SCENARIO`, or "
          "`all` for every channel without its own entry), each datagram independently: `drop`, "
          "`duplicate` (sent twice), `reorder` (held back until the next datagram on the channel has "
          "gone, at most 20 ms), `corrupt` (one byte flipped; caught by the message checksum or the "
          "decoder, and then like a lost datagram) — probabilities 0–1, default 0 — and `delay` plus "
          "uniform `delay_jitter` [s] ≥ 0, default 0. Counted in `summary.json` "
          "(`messages.CHANNEL.injected`). Example: `--set 'faults.channels.all={drop: 0.05, duplicate: "
          "0.05, reorder: 0.05}'`."),
      inside("faults.channels.NAME.corrupt", "faults.channels.NAME", probability()),
      inside("faults.channels.NAME.delay", "faults.channels.NAME", faultDelay()),
      inside("faults.channels.NAME.delay_jitter", "faults.channels.NAME", faultDelay()),
      inside("faults.channels.NAME.drop", "faults.channels.NAME", probability()),
      inside("faults.channels.NAME.duplicate", "faults.channels.NAME", probability()),
      inside("faults.channels.NAME.reorder", "faults.channels.NAME", probability()),
      row("faults.receivers.PROCESS.drop", "probability 0–1", "none",
          "a loss only PROCESS (`plant`, `controller`, `actuator`, `logger`) sees: each datagram that "
          "reaches it, on any channel, is dropped before it is recorded or decoded — as a datagram "
          "lost on the way to one host of a real network. The draw is a seeded hash of the datagram's "
          "bytes (a re-sent copy draws again). Counted in `summary.json` "
          "(`messages.CHANNEL.injected.lost_on_receive`). Example: `--set "
          "'faults.receivers.logger={drop: 0.05}'`: in lockstep the log is still complete, since the "
          "plant re-sends every tick the logger has not confirmed.",
          probability()),
      row("sensors.seed", "integer ≥ 0", "1",
          "seeds the sensor noise's draws: the same seed gives the same readings in lockstep, "
          "realtime, in-process and replay. Without a `sensors` section PLANT_POSITION carries the "
          "true angles. A sensor model registered by `plant::registerSensorModel` in programs built "
          "with it (docs/extending.md, \"Adding a sensor model\") adds its own per-joint keys to "
          "every sensor's section below.",
          seed()),
      row("sensors.position.counts_per_revolution", "vector or scalar, whole numbers ≥ 0", "0",
          "the joint encoder's resolution, N: PLANT_POSITION carries floor(angle / Δ) Δ, Δ = 2π / N "
          "(the count below the angle, as an incremental encoder counts: half a count of bias on "
          "average); 0: not quantised. PLANT_TRUTH keeps the true angles (plant/joint_sensor.hpp).",
          counts()),
      row("sensors.position.noise_sigma", "vector or scalar ≥ 0", "0",
          "standard deviation of a Gaussian noise added to each reading before quantisation [rad], one "
          "draw per joint and tick.",
          noise()),
      row("sensors.position.delay", "integer ≥ 0", "0",
          "the reading of tick k is of the angle at tick k − delay (whole samples; before that, the "
          "angle at tick 0).",
          sensorDelay()),
      row("sensors.velocity.noise_sigma", "vector or scalar ≥ 0", "0",
          "a `sensors.velocity` section declares a velocity sensor (tachometer) on every joint: the "
          "plant publishes its reading on PLANT_RATE, just before the PLANT_POSITION of the same tick. "
          "Only with it may a controller that measures the velocity (`pd_plus`, `slotine_li`) run; the "
          "paper's controllers and the observer-based baselines never receive it. `sensors: {velocity: "
          "{}}` declares an exact one; its draws are its own (the position sensor's do not change when "
          "it is added). This key: the standard deviation of a Gaussian noise added to each rate "
          "reading [rad/s], one draw per joint and tick.",
          noise()),
      row("sensors.velocity.delay", "integer ≥ 0", "0",
          "the rate reading of tick k is of the rate at tick k − delay (whole samples).", sensorDelay()),
      row("sensors.motor.counts_per_revolution", "vector or scalar, whole numbers ≥ 0", "0",
          "a `sensors.motor` section (flexible joints only, `robot.flexible`) declares a sensor on the "
          "motor angles q2, which PLANT_MOTOR then carries instead of the true ones; the motor rates "
          "q2' (`robot.flexible.rate_sensor`) stay exact, and its draws are its own. This key: the "
          "motor encoder's resolution, as `sensors.position.counts_per_revolution`.",
          counts()),
      row("sensors.motor.noise_sigma", "vector or scalar ≥ 0", "0",
          "noise on each motor-angle reading [rad], as `sensors.position.noise_sigma`.", noise()),
      row("sensors.motor.delay", "integer ≥ 0", "0", "the motor reading of tick k is of tick k − delay.",
          sensorDelay()),
  };
}

// What `lagrange compare` runs.
std::vector<KeyInfo> compareKeys() {
  return {
      row("compare.controllers.TYPE", "map of TYPE's keys", "absent",
          "`lagrange compare` only (docs/comparison.md; `lagrange run` carries it along and ignores "
          "it): a controller to compare, TYPE its `controller.type`, the map its other `controller.*` "
          "keys (e.g. `pd_plus: {kp: [150, 10], kd: [15, 1]}`); its run gets `controller = {type: "
          "TYPE, …}`. An empty map for the scenario's own `controller.type` keeps the `controller` "
          "section as it is. With a `type` key inside, TYPE is only the row's name: e.g. "
          "`pd_python: {type: external, command: [python3, pd_controller.py, ...]}` compares an external "
          "program (run in lockstep, the others in process). In file order; `--controllers` picks some"),
      row("compare.sweep.key", "a dotted key", "absent",
          "`lagrange compare` also runs every controller for each value of this key (e.g. "
          "`sensors.position.counts_per_revolution`, `sensors.position.noise_sigma`, "
          "`plant.publish_rate`) and plots the steady-state error against it; `--sweep` overrides"),
      row("compare.sweep.values", "list", "required with `key`",
          "the values, each as it would be written after `--set KEY=`"),
  };
}

// The rows registered by the files that own their keys (registerKeyRows),
// by the variant they were registered as.
std::map<std::string, std::vector<KeyInfo>>& registeredRows() {
  static std::map<std::string, std::vector<KeyInfo>> rows;
  return rows;
}
// What each variant of a section is, for messages: "a key of <this>".
std::map<std::string, std::string>& variantDescriptions() {
  static std::map<std::string, std::string> descriptions = {
      {"sine", "reference.type sine and smooth_sine only"},
      {"free_motion", "reference.type free_motion only"},
      {"external", "controller.type external only"},
      {"external_plant", "plant.type external only"}};
  return descriptions;
}
bool& tableBuilt() {
  static bool built = false;
  return built;
}

// By the variant registered, so that the order does not hang on the order
// of static initialisers across files.
std::vector<KeyInfo> registeredControllerKeys() {
  std::vector<KeyInfo> rows;
  for (const auto& [variant, of_variant] : registeredRows())
    rows.insert(rows.end(), of_variant.begin(), of_variant.end());
  return rows;
}

// The sections in the order of docs/configuration.md.
std::vector<KeyInfo> makeTable() {
  std::vector<KeyInfo> table;
  for (std::vector<KeyInfo> (*section)() :
       {runKeys, armKeys, referenceKeys, plantAndActuatorKeys, controllerKeys, registeredControllerKeys,
        judgementKeys, faultAndSensorKeys, compareKeys}) {
    std::vector<KeyInfo> keys = section();
    table.insert(table.end(), std::make_move_iterator(keys.begin()), std::make_move_iterator(keys.end()));
  }
  tableBuilt() = true;
  return table;
}

}  // namespace

void registerKeyRows(const std::string& variant, const std::string& description, std::vector<KeyInfo> rows) {
  if (tableBuilt())
    throw std::logic_error("config::registerKeyRows: called after the key table was first read");
  if (!variantDescriptions().emplace(variant, description).second)
    throw std::logic_error("config::registerKeyRows: variant '" + variant + "' is registered twice");
  registeredRows()[variant] = std::move(rows);
}

const std::string& variantDescription(const std::string& variant) {
  const auto it = variantDescriptions().find(variant);
  if (it == variantDescriptions().end())
    throw std::logic_error("config::variantDescription: no variant '" + variant + "'");
  return it->second;
}

const std::vector<KeyInfo>& keyTable() {
  static const std::vector<KeyInfo> table = makeTable();
  return table;
}

std::set<std::string> keysUnder(const std::string& section, const std::string& variant) {
  const std::string prefix = section.empty() ? "" : section + ".";
  std::map<std::string, std::string> variant_of;
  for (const KeyInfo& k : keyTable()) variant_of[k.key] = k.variant;
  std::set<std::string> keys;
  for (const KeyInfo& k : keyTable()) {
    if (k.key.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = k.key.substr(prefix.size());
    const std::string child = rest.substr(0, rest.find_first_of(".["));
    // The child's own row decides ("controller.stages" is the paper
    // controllers', and so is every key below it); a section that is no key
    // of its own ("robot.urdf") goes by the key that put it here.
    const auto own = variant_of.find(prefix + child);
    const std::string& of = own != variant_of.end() ? own->second : k.variant;
    if (of.empty() || of == variant) keys.insert(child);
  }
  // A reader asking for a section the table lacks would refuse every key
  // with an empty list: a programming error, said at once.
  if (keys.empty())
    throw std::logic_error("config::keysUnder: no key of the key table is under '" + section + "'");
  return keys;
}

}  // namespace lagrange::config
