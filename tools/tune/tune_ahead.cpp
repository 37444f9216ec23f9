#include "tools/tune/tune_ahead.hpp"

#include <algorithm>
#include <system_error>

namespace lagrange::tools {

CandidateRuns::CandidateRuns(const TuneProblem& p, int workers, bool (*stop_requested)(),
                             const std::atomic<double>* cut_time)
    : problem_(p), stop_requested_(stop_requested), cut_time_(cut_time) {
  for (int i = 0; workers > 1 && i < workers; ++i) {
    try {
      workers_.emplace_back([this] { work(); });
    } catch (const std::system_error&) {  // no thread to be had: fewer make the same runs
      break;
    }
  }
}

CandidateRuns::~CandidateRuns() { finish(); }

void CandidateRuns::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
    queue_.clear();
  }
  changed_.notify_all();
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

void CandidateRuns::ahead(const std::vector<std::vector<double>>& points) {
  if (workers_.empty()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const std::vector<double>& q : queue_) slots_.erase(q);  // not started: dropped
    queue_.clear();
    for (auto it = slots_.begin(); it != slots_.end();)
      if (it->second->done && std::find(points.begin(), points.end(), it->first) == points.end())
        it = slots_.erase(it);
      else
        ++it;
    for (const std::vector<double>& point : points)
      if (slots_.emplace(point, std::make_shared<Slot>()).second) queue_.push_back(point);
  }
  changed_.notify_all();
}

CandidateRun CandidateRuns::runHere(const std::vector<double>& point) {
  return runCandidate(problem_, gainsOf(problem_, point), stop_requested_, cut_time_);
}

CandidateRun CandidateRuns::take(const std::vector<double>& point) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto it = slots_.find(point);
  if (it == slots_.end() || !it->second->started) {
    // Not under way: made here (and no worker will start it).
    if (it != slots_.end()) {
      queue_.erase(std::remove(queue_.begin(), queue_.end(), point), queue_.end());
      slots_.erase(it);
    }
    ++made_;
    ++used_;
    lock.unlock();
    CandidateRun run = runHere(point);
    lock.lock();
    cut_ += run.findings.status == "cut";
    return run;
  }
  const std::shared_ptr<Slot> slot = it->second;
  changed_.wait(lock, [&] { return slot->done; });
  slots_.erase(point);
  ++used_;
  if (slot->error) std::rethrow_exception(slot->error);
  cut_ += slot->run.findings.status == "cut";
  return std::move(slot->run);
}

void CandidateRuns::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return closing_ || !queue_.empty(); });
    if (closing_) return;
    const std::vector<double> point = queue_.front();
    queue_.pop_front();
    const std::shared_ptr<Slot> slot = slots_.at(point);
    slot->started = true;
    ++made_;
    ++made_ahead_;
    lock.unlock();
    CandidateRun run;
    std::exception_ptr error;
    try {
      run = runHere(point);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    slot->run = std::move(run);
    slot->error = error;
    slot->done = true;
    changed_.notify_all();
  }
}

int CandidateRuns::made() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return made_;
}
int CandidateRuns::madeAhead() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return made_ahead_;
}
int CandidateRuns::used() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return used_;
}
int CandidateRuns::cut() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return cut_;
}

}  // namespace lagrange::tools
