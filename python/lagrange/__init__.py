"""lagrange for Python: the message types, a reader of run logs, LCM through
Debian's liblcm1, and helpers for controllers and plants of your own.

    lagrange.run(scenario, ...)       runs `lagrange run`, returns what lagrange.log.load does
    lagrange.sweep(spec, ...)         runs `lagrange sweep`, returns its rows (lagrange/programs.py)
    lagrange.log.load(run_dir)        a run's log as per-channel arrays (lagrange/log.py)
    lagrange.logfile.LogReader(path)  the events of any LCM log, bounds-checked
    lagrange.lcm.LCM(url)             LCM itself, through ctypes (lagrange/lcm.py)
    lagrange.external.run(step)       an external controller: you write step(t, q) -> u
    lagrange.external_plant.run(step) an external plant: you write step(t, u, dt) -> (q, qdot)
    lagrange.contract                 the wire contract: MAC, checksum, headers

The message classes (lagrange.plant_position_t, ...) are lcm-gen's Python
output for lcmtypes/*.lcm, checked in; a test holds them to what lcm-gen
writes. Standard library only; numpy is used when present, never required.
"""

__version__ = "0.1.0"

# lcm-gen's own package file imports the types the same way: the generated
# modules refer to one another as lagrange.header_t, the class.
from .actuator_state_t import actuator_state_t
from .channel_stats_t import channel_stats_t
from .control_command_t import control_command_t
from .header_t import header_t
from .loop_stats_t import loop_stats_t
from .plant_motor_t import plant_motor_t
from .plant_position_t import plant_position_t
from .plant_rate_t import plant_rate_t
from .plant_truth_t import plant_truth_t
from .robot_description_t import robot_description_t
from .run_join_t import run_join_t
from .scenario_t import scenario_t
from .status_t import status_t

from .programs import LagrangeError, run, sweep  # noqa: E402  (after the types: log needs them)
from .tune import tune  # noqa: E402  (lagrange tune, docs/tuning.md)
