#include "tools/view/view_source.hpp"

#include "config/robot_description_lcm.hpp"
#include "transport/channels.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {
// One intact message of this run, as a log's are checked.
template <class Msg>
bool decodeLive(const lcm::ReceiveBuffer& buffer, int64_t run_id, Msg& m) {
  if (!logs::decodeSkippingTrailer(buffer.data, buffer.data_size, m)) return false;
  if constexpr (transport::HasHeader<Msg>::value) return run_id == 0 || m.header.run_id == run_id;
  return true;
}

// The channels a frame is made of, for the log and the live feed alike:
// decodes a message of `channel` with `decode` into the assembler. True if
// it is one of them and decoded.
template <class Decode>
bool addToFrames(const std::string& channel, FrameAssembler& assembler, const Decode& decode) {
  auto add = [&](auto m) {
    if (!decode(m)) return false;
    assembler.add(m);
    return true;
  };
  if (channel == transport::kPlantTruth) return add(lagrange::plant_truth_t{});
  if (channel == transport::kControlCommand) return add(lagrange::control_command_t{});
  if (channel == transport::kPlantMotor) return add(lagrange::plant_motor_t{});
  return false;
}
}  // namespace

ViewLog readViewLog(const std::string& path) {
  ViewLog out;
  bool described = false;
  bool any_truth = false;
  std::optional<std::string> scenario;
  FrameAssembler assembler;
  out.scan = logs::readLog(path, [&](const lcm::LogEvent& ev) {
    if (ev.channel == transport::kScenario) {
      if (!scenario) scenario = logs::scenarioYaml(ev);
    } else if (ev.channel == transport::kRobotDescription) {
      if (!described)
        described = logs::decodeEvent(ev, out.description) && descriptionProblem(out.description).empty();
    } else {
      const bool added =
          addToFrames(ev.channel, assembler, [&](auto& m) { return logs::decodeEvent(ev, m); });
      any_truth = any_truth || (added && ev.channel == transport::kPlantTruth);
    }
  });
  // A log recorded before ROBOT_DESCRIPTION existed: its arm from its scenario.
  if (!described && scenario) {
    try {
      out.description =
          config::robotDescriptionMessage(config::parseLoggedScenario(*scenario, path + " (SCENARIO)"));
      described = true;
      out.notes.push_back(
          "no ROBOT_DESCRIPTION in the log (recorded before it existed): the arm is drawn from "
          "its SCENARIO");
    } catch (const std::exception& e) {
      throw logs::LogError(path + " holds no ROBOT_DESCRIPTION message and its SCENARIO cannot be read (" +
                           e.what() + "); expected a log of `lagrange run`, or of lcm-logger during one");
    }
  }
  if (!described)
    throw logs::LogError(path +
                         " holds neither ROBOT_DESCRIPTION nor SCENARIO: nothing says what arm to draw; "
                         "expected a log of `lagrange run`, or of lcm-logger during one");
  if (!any_truth)
    throw logs::LogError(
        path + " holds no PLANT_TRUTH message: nothing to draw; expected a log of a run that started");
  out.frames = assembler.take(true);
  return out;
}

LiveFeed::LiveFeed(const std::string& lcm_url, int64_t run_id,
                   const std::optional<transport::MessageKey>& key, size_t capacity)
    : lcm_(lcm_url),
      run_id_(run_id),
      auth_(key ? std::make_unique<transport::MessageAuthenticator>(*key) : nullptr),
      capacity_(capacity) {
  if (!lcm_.good()) throw RuntimeFault("LCM cannot open " + (lcm_url.empty() ? "its default URL" : lcm_url));
  for (const char* channel : {transport::kRobotDescription, transport::kPlantTruth,
                              transport::kControlCommand, transport::kPlantMotor})
    lcm_.subscribeFunction(
        channel,
        +[](const lcm::ReceiveBuffer* buffer, const std::string& name, LiveFeed* self) {
          self->onMessage(buffer, name);
        },
        this);
  thread_ = std::thread([this] { loop(); });
}

LiveFeed::~LiveFeed() {
  stop_ = true;
  thread_.join();
}

void LiveFeed::loop() {
  while (!stop_) {
    if (lcm_.handleTimeout(50) < 0) break;
    std::vector<ViewFrame> ready = assembler_.take(false);
    if (ready.empty()) continue;
    std::lock_guard<std::mutex> lock(mutex_);
    for (ViewFrame& f : ready) frames_.push_back(std::move(f));
    while (frames_.size() > capacity_) {
      frames_.pop_front();
      ++first_index_;
    }
    changed_.notify_all();
  }
}

void LiveFeed::onMessage(const lcm::ReceiveBuffer* received, const std::string& channel) {
  // With the run's key: the datagram's MAC checked before anything is
  // decoded, and the payload without it. Without: decodeLive skips a trailer.
  lcm::ReceiveBuffer payload = *received;
  const lcm::ReceiveBuffer* buffer = &payload;
  if (auth_) {
    if (!auth_->verify(static_cast<const uint8_t*>(received->data), received->data_size)) {
      ++rejected_;
      return;
    }
    payload.data_size -= static_cast<uint32_t>(transport::kMacBytes);
  }
  bool ok = false;
  if (channel == transport::kRobotDescription) {
    lagrange::robot_description_t m;
    ok = decodeLive(*buffer, run_id_, m) && descriptionProblem(m).empty();
    if (ok) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!description_) {
        description_ = std::move(m);
        changed_.notify_all();
      }
    }
  } else {
    ok = addToFrames(channel, assembler_, [&](auto& m) { return decodeLive(*buffer, run_id_, m); });
  }
  ++(ok ? received_ : rejected_);
}

LiveFeed::Update LiveFeed::waitFrom(uint64_t from, size_t max_frames, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t end = first_index_ + frames_.size();
  if (from >= end) changed_.wait_for(lock, timeout, [&] { return first_index_ + frames_.size() > from; });
  Update u;
  u.description = description_;
  const uint64_t begin = std::max(from, first_index_);
  const uint64_t stop = first_index_ + frames_.size();
  u.next = stop;
  if (begin >= stop) return u;
  const uint64_t count = stop - begin;
  const uint64_t stride = max_frames == 0 ? 1 : (count + max_frames - 1) / max_frames;
  // Spread evenly, counted back from the newest, so the newest is always sent.
  std::vector<ViewFrame> picked;
  for (uint64_t k = stop; k > begin; k -= std::min(stride, k - begin))
    picked.push_back(frames_[k - 1 - first_index_]);
  u.frames.assign(picked.rbegin(), picked.rend());
  return u;
}

}  // namespace lagrange::tools
