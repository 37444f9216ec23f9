#pragma once
/// @file
/// The rules of `lagrange run`'s launcher that need no process or file:
/// which processes start on this host and what a partial launch needs, the
/// identity launchers on several hosts agree on, and when a dead process is
/// restarted.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "config/scenario.hpp"
#include "tools/run/run_command.hpp"

namespace lagrange::tools {

/// True when `process` starts here: no --processes, or it is among them.
bool runsHere(const RunOptions& opt, const std::string& process);

/// "" when --processes is usable, else what is wrong and what is expected:
/// an unknown process, or a partial launch without --no-netns, --lcm-url or
/// --key-file (the other hosts could not hear or verify it).
std::string checkProcesses(const RunOptions& opt);

/// The run identity of a run spread over hosts: derived from what they share,
/// the URL and the resolved scenario's text, so each launcher finds the same
/// without talking; positive and never 0 ("any run"). (FNV-1a with the offset
/// basis 1469598103934665603, one digit short of the standard one: kept, so
/// hosts of different versions of this project still agree.)
int64_t sharedRunId(const std::string& lcm_url, const std::string& resolved_text);

/// How a plant that exited with code 0 ended the run short, from the
/// logger's summary.json of this run (its `status`, `mode`, the plant's
/// last STATUS in `processes.plant`, `log.missing_ticks`): "" when the run
/// completed, when there is no summary, or when the plant said "finished"
/// at the last tick of a realtime run (a last sample lost on the way is no
/// plant's fault). A plant that says "finished" early, leaves a lockstep
/// log with gaps, or exits without a word fails the run named as the plant --
/// not the logger, which only waited, and not silently "interrupted".
std::string plantEndedEarly(const nlohmann::json& summary, long long last_tick);

/// summary.json's `supervision` before anything died: the policy
/// ("restart"), no "restarts", no "deaths".
nlohmann::json supervisionRecord(const config::SupervisionConfig& policy);

/// A dead process is restarted when the scenario's supervision names it and
/// it has restarts left. Every death is noted in `supervision` either way
/// ("deaths": process, how, restarted; "restarts": per process) in
/// `supervision`, made by supervisionRecord.
bool mayRestart(const config::SupervisionConfig& policy, nlohmann::json& supervision,
                const std::string& process, const std::string& how_it_died);

}  // namespace lagrange::tools
