#pragma once
/// @file
/// Where `lagrange view` takes its frames from: a whole log read at start
/// (ViewLog), or a running scenario's LCM traffic (LiveFeed), both through
/// the FrameAssembler.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "lagrange/robot_description_t.hpp"
#include "logs/log_reader.hpp"
#include "tools/view/view_frames.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::tools {

struct ViewLog {
  lagrange::robot_description_t description;
  std::vector<ViewFrame> frames;
  logs::LogScan scan;
  std::vector<std::string> notes;  ///< how it was read, for a person (shown with the scan's problems)
};

/// Reads a log of `lagrange run` or of lcm-logger during one.
/// A log recorded before ROBOT_DESCRIPTION existed is drawn from its
/// SCENARIO (its arm built again from the configuration; a URDF must be where
/// the scenario names it). @throws LogError if it cannot be read, says
/// nothing of its arm, or holds no PLANT_TRUTH.
ViewLog readViewLog(const std::string& path);

/// A running scenario's messages, assembled into frames by a thread of its
/// own. Keeps the newest `capacity` frames.
class LiveFeed {
 public:
  /// run_id 0 accepts every run on the URL. With `key`, only datagrams
  /// carrying its MAC are read (the run's own check, before decoding);
  /// without, a run's MAC trailer is skipped unchecked and anyone on the
  /// group can draw into the page (runView says so). @throws
  /// RuntimeFault if LCM cannot open `lcm_url`.
  LiveFeed(const std::string& lcm_url, int64_t run_id, const std::optional<transport::MessageKey>& key,
           size_t capacity = 200000);
  ~LiveFeed();
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  struct Update {
    std::optional<lagrange::robot_description_t> description;
    std::vector<ViewFrame>
        frames;         ///< from index `from` on, at most max_frames spread evenly, the newest last
    uint64_t next = 0;  ///< the index to ask for next
  };
  /// Waits up to `timeout` for frames with index >= from (indices count every
  /// frame since the start), then returns what there is.
  Update waitFrom(uint64_t from, size_t max_frames, std::chrono::milliseconds timeout);

  /// Messages received and decoded, and rejected (undecodable, corrupted or of another run).
  uint64_t received() const { return received_; }
  uint64_t rejected() const { return rejected_; }

 private:
  void onMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void loop();

  lcm::LCM lcm_;
  int64_t run_id_;
  std::unique_ptr<transport::MessageAuthenticator> auth_;
  size_t capacity_;
  FrameAssembler assembler_;  // the LCM thread's only
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<lagrange::robot_description_t> description_;
  std::deque<ViewFrame> frames_;
  uint64_t first_index_ = 0;  ///< index of frames_.front()
  std::atomic<uint64_t> received_{0}, rejected_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace lagrange::tools
