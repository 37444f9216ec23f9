#pragma once
/// @file
/// `lagrange tune --slurm` and `lagrange tune collect DIR` (docs/tuning.md,
/// "On a Slurm cluster"). One search asks for one point at a time, each a
/// run of a second or less -- less than a cluster job's scheduling -- so a
/// cluster runs independent searches instead: start K is exactly
/// `lagrange tune ... --seed SEED+K --out DIR/starts/K`, one array task each,
/// and the result is the best any start found. DIR/starts.json keeps the
/// arguments (a rerun resubmits only the starts not finished, each resuming
/// its own tune.jsonl); collect writes DIR/tuned.yaml, DIR/tune.json and
/// DIR/front.png from the starts.

#include <string>

#include "tools/tune/tune.hpp"

namespace lagrange::tools {

/// Submits the starts not yet finished as a job array, waits for it (unless
/// --no-wait) and collects. Exit codes as collectTune's; 130 when the
/// waiting was stopped (the job keeps running).
int runTuneSlurm(const TuneOptions& options);

/// The best of DIR's starts into DIR/tuned.yaml, DIR/tune.json, DIR/front.png;
/// `who` begins each message (`lagrange tune` when the tune itself collects).
/// Exit 0 when every start finished and one found gains that pass every
/// check; 1 when a start is not finished (tuned.yaml then holds the best of
/// those that are) or none passed (what binds is named); 2 for a DIR that is
/// not a Slurm tune's, or a start folder that is not its start's.
int collectTune(const std::string& dir, bool quiet, const std::string& who = "lagrange tune collect");

}  // namespace lagrange::tools
