// The C++ SDK's plant guards (limits, watchdog, stale-torque choice): filled in next.
