#pragma once
/// @file
/// `lagrange tune`, its candidates' runs made ahead of the search's asking,
/// on `workers` threads (tune's -j): the search hands over the points it
/// will ask for next (SearchLookahead, tools/tune/tune_search.hpp), the
/// workers run them from the initial state (runCandidate), and the search's
/// sequential step takes each run when it asks for it. What a run finds
/// depends on its gains alone, so the evaluations are those made one at a
/// time, in the same order: only the wall time differs.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "tools/tune/tune_evaluate.hpp"

namespace lagrange::tools {

class CandidateRuns {
 public:
  /// `workers` threads (none for 0 or 1: take() then runs each itself).
  /// `p`, `stop_requested` and `cut_time` (runCandidate's; may be null)
  /// must outlive this object.
  CandidateRuns(const TuneProblem& p, int workers, bool (*stop_requested)(),
                const std::atomic<double>* cut_time = nullptr);
  ~CandidateRuns();  ///< as finish()
  /// Drops the queued runs and waits for those in progress (a stop request
  /// ends them early): the search is over, its guesses must not hold a core.
  void finish();
  CandidateRuns(const CandidateRuns&) = delete;
  CandidateRuns& operator=(const CandidateRuns&) = delete;

  /// Queues the runs of `points`, in order (the first is the search's next
  /// call). Queued runs of an earlier call that no worker has started are
  /// dropped, as are finished runs not among `points`: the search has moved on.
  void ahead(const std::vector<std::vector<double>>& points);
  /// The run of `point`: a worker's (waiting for it if it is under way), or
  /// made here. Rethrows what the run threw.
  CandidateRun take(const std::vector<double>& point);

  /// Runs made (by a worker or in take()), those a worker made, and those
  /// a take() used (the rest were guesses the search did not ask for);
  /// cut(): the runs taken that were stopped at a cut.
  int made() const;
  int madeAhead() const;
  int used() const;
  int cut() const;

 private:
  struct Slot {
    bool started = false, done = false;
    CandidateRun run;
    std::exception_ptr error;
  };
  void work();
  CandidateRun runHere(const std::vector<double>& point);

  const TuneProblem& problem_;
  bool (*stop_requested_)();
  const std::atomic<double>* cut_time_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::vector<double>, std::shared_ptr<Slot>> slots_;
  std::deque<std::vector<double>> queue_;
  bool closing_ = false;
  int made_ = 0, made_ahead_ = 0, used_ = 0, cut_ = 0;
  std::vector<std::thread> workers_;
};

}  // namespace lagrange::tools
