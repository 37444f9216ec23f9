// The log reader on crafted bytes: it reads what LCM's own writer writes,
// refuses a header whose lengths no log can hold (naming the file, the byte
// offset and what was expected) before allocating anything, skips a corrupt
// stretch to the next whole event, and reads a log cut at any byte up to its
// last whole event.
#include "logs/log_reader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <vector>

namespace lagrange::tools {
namespace {

namespace fs = std::filesystem;

void putBigEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

// One event as the LCM log format lays it out, lengths as given (they may lie).
std::string eventBytes(int64_t number, const std::string& channel, const std::string& data,
                       int32_t channel_length, int32_t data_length, uint32_t sync = 0xEDA1DA01u) {
  std::string out;
  putBigEndian(out, sync, 4);
  putBigEndian(out, static_cast<uint64_t>(number), 8);
  putBigEndian(out, static_cast<uint64_t>(1700000000000000 + number), 8);  // timestamp [us]
  putBigEndian(out, static_cast<uint32_t>(channel_length), 4);
  putBigEndian(out, static_cast<uint32_t>(data_length), 4);
  return out + channel + data;
}

std::string event(int64_t number, const std::string& channel, const std::string& data) {
  return eventBytes(number, channel, data, static_cast<int32_t>(channel.size()),
                    static_cast<int32_t>(data.size()));
}

class LogFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lagrange-log-reader-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& bytes, const std::string& name = "crafted.lcm") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  struct Read {
    std::vector<std::string> channels, data;
    std::vector<int64_t> numbers;
    logs::LogScan scan;
  };
  static Read read(const std::string& path) {
    Read r;
    r.scan = logs::readLog(path, [&](const lcm::LogEvent& ev) {
      r.channels.push_back(ev.channel);
      r.data.emplace_back(static_cast<const char*>(ev.data), static_cast<std::size_t>(ev.datalen));
      r.numbers.push_back(ev.eventnum);
    });
    return r;
  }
  // The LogError reading `path` throws, or "" if none.
  static std::string refusal(const std::string& path) {
    try {
      read(path);
    } catch (const logs::LogError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(LogFileTest, ReadsWhatLcmsOwnWriterWrote) {
  const std::string path = (dir_ / "lcm.lcm").string();
  const std::vector<std::pair<std::string, std::string>> written = {
      {"SCENARIO", "name: x"}, {"PLANT_TRUTH", std::string("\x00\x01\x02\xff", 4)}, {"EMPTY", ""}};
  {
    lcm::LogFile log(path, "w");
    for (const auto& [channel, data] : written) {
      lcm::LogEvent ev{};
      ev.channel = channel;
      ev.data = const_cast<char*>(data.data());
      ev.datalen = static_cast<int32_t>(data.size());
      ev.timestamp = 42;
      log.writeEvent(&ev);
    }
  }
  const Read r = read(path);
  ASSERT_EQ(r.channels.size(), written.size());
  for (size_t i = 0; i < written.size(); ++i) {
    EXPECT_EQ(r.channels[i], written[i].first);
    EXPECT_EQ(r.data[i], written[i].second);
    EXPECT_EQ(r.numbers[i], static_cast<int64_t>(i));
  }
  EXPECT_TRUE(r.scan.problems().empty());
  EXPECT_EQ(r.scan.channels.at("PLANT_TRUTH"), 1);
}

TEST_F(LogFileTest, AHugeDataLengthIsRefusedWithItsOffsetAndTheBytesLeft) {
  const std::string good = event(0, "SCENARIO", "name: x") + event(1, "PLANT_TRUTH", "12345678");
  const std::string path = write(good + eventBytes(2, "PLANT_TRUTH", "1234", 11, 0x7fffffff));
  const std::string why = refusal(path);
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_NE(why.find("the event at byte " + std::to_string(good.size()) + " "), std::string::npos) << why;
  EXPECT_NE(why.find("data length of 2147483647 bytes; expected 0 to 268435456"), std::string::npos) << why;
  EXPECT_NE(why.find("at most the 4 bytes left in the file"), std::string::npos) << why;
}

TEST_F(LogFileTest, AHugeOrNegativeChannelLengthIsRefusedWithItsOffset) {
  const std::string good = event(0, "SCENARIO", "name: x");
  for (const int32_t length : {0x7fffffff, 1000, 0, -1, static_cast<int32_t>(0x80000000)}) {
    const std::string path = write(good + eventBytes(1, "PLANT_TRUTH", "abc", length, 3));
    const std::string why = refusal(path);
    EXPECT_NE(
        why.find("the event at byte " + std::to_string(good.size()) + " gives a channel name length of " +
                 std::to_string(length) + " bytes; expected 1 to 999"),
        std::string::npos)
        << why;
  }
}

TEST_F(LogFileTest, ANegativeDataLengthIsRefusedWithItsOffset) {
  // The first event: a log that is malformed from byte 0 is refused too, not taken for "no event".
  const std::string path = write(eventBytes(0, "PLANT_TRUTH", "abc", 11, -3) + event(1, "SCENARIO", "x"));
  const std::string why = refusal(path);
  EXPECT_NE(why.find(path + ": malformed LCM log: the event at byte 0 gives a data length of -3 bytes"),
            std::string::npos)
      << why;
}

TEST_F(LogFileTest, ABadSyncWordAfterGoodEventsIsSkippedToTheNextWholeEvent) {
  const std::string good = event(0, "SCENARIO", "name: x") + event(1, "PLANT_TRUTH", "12345678");
  // Junk where the third event should start, with a chance sync word inside
  // it whose lengths are impossible: part of the junk, not a malformed event.
  std::string junk = eventBytes(2, "PLANT_TRUTH", "abcd", 11, 4, 0x5A5A5A5Au);
  junk += eventBytes(3, "X", "", 0x7fffffff, 0x7fffffff);
  const std::string path = write(good + junk + event(4, "CONTROL_COMMAND", "after"));
  const Read r = read(path);
  EXPECT_EQ(r.channels, (std::vector<std::string>{"SCENARIO", "PLANT_TRUTH", "CONTROL_COMMAND"}));
  EXPECT_EQ(r.data.back(), "after");
  EXPECT_EQ(r.numbers.back(), 4);
  EXPECT_EQ(r.scan.skipped_bytes, static_cast<long long>(junk.size()));
  EXPECT_EQ(r.scan.first_skipped_at, static_cast<long long>(good.size()));
  EXPECT_EQ(r.scan.unreadable_tail_bytes, 0);
  ASSERT_EQ(r.scan.problems().size(), 1u);
  EXPECT_NE(r.scan.problems()[0].find(std::to_string(junk.size()) +
                                      " corrupt bytes between events were skipped (the events there are "
                                      "lost; the first stretch starts at byte " +
                                      std::to_string(good.size())),
            std::string::npos)
      << r.scan.problems()[0];

  // The same junk with nothing whole behind it is the log's unreadable end.
  const Read end = read(write(good + junk, "junk-end.lcm"));
  EXPECT_EQ(end.channels.size(), 2u);
  EXPECT_EQ(end.scan.skipped_bytes, 0);
  EXPECT_EQ(end.scan.unreadable_tail_bytes, static_cast<long long>(junk.size()));
}

// A logger killed while writing: cut at any byte, the log reads up to its
// last whole event, and the rest is counted as its unreadable end.
TEST_F(LogFileTest, ALogCutAtAnyByteReadsUpToItsLastWholeEvent) {
  const std::vector<std::string> events = {event(0, "SCENARIO", "name: x"),
                                           event(1, "PLANT_TRUTH", "12345678"),
                                           event(2, "CONTROL_COMMAND", std::string(300, '\xED'))};
  std::string whole;
  std::vector<size_t> ends;
  for (const std::string& e : events) ends.push_back((whole += e).size());
  for (size_t cut = 1; cut <= whole.size(); ++cut) {
    const std::string path = write(whole.substr(0, cut));
    size_t complete = 0;
    while (complete < ends.size() && ends[complete] <= cut) ++complete;
    if (complete == 0) {
      EXPECT_NE(refusal(path).find("is not an LCM log: no event in its " + std::to_string(cut) + " bytes"),
                std::string::npos)
          << "cut at " << cut;
      continue;
    }
    const Read r = read(path);
    EXPECT_EQ(r.channels.size(), complete) << "cut at " << cut;
    EXPECT_EQ(r.scan.skipped_bytes, 0) << "cut at " << cut;
    EXPECT_EQ(r.scan.unreadable_tail_bytes, static_cast<long long>(cut - ends[complete - 1]))
        << "cut at " << cut;
    EXPECT_EQ(r.scan.problems().empty(), cut == ends[complete - 1]) << "cut at " << cut;
  }
}

// A plausible length that runs past the end is a cut, not a malformed log:
// what a killed logger leaves is indistinguishable from it.
TEST_F(LogFileTest, ASaneLengthPastTheEndIsTheLogsCutEnd) {
  const std::string good = event(0, "SCENARIO", "name: x");
  const Read r = read(write(good + eventBytes(1, "PLANT_TRUTH", "only these", 11, 100000)));
  EXPECT_EQ(r.channels.size(), 1u);
  EXPECT_EQ(r.scan.unreadable_tail_bytes, 28 + 11 + 10);
}

TEST_F(LogFileTest, WhatIsNotALogFileIsNamed) {
  EXPECT_NE(refusal(write("hello\n")).find("is not an LCM log: no event in its 6 bytes"), std::string::npos);
  EXPECT_NE(refusal(dir_.string()).find("'" + dir_.string() + "' is a directory; expected an LCM log file"),
            std::string::npos);
  EXPECT_NE(refusal((dir_ / "missing.lcm").string()).find("cannot read"), std::string::npos);
  const Read empty = read(write(""));  // an empty log: no event, nothing lost
  EXPECT_EQ(empty.scan.events, 0);
  EXPECT_TRUE(empty.scan.problems().empty());
}

// Random damage to a real-looking log never crashes, and every byte is
// accounted for: read as an event, skipped, or the unreadable end.
TEST_F(LogFileTest, RandomDamageIsReadRefusedOrSkippedAndEveryByteIsAccountedFor) {
  std::mt19937 rng(28);
  std::string clean;
  for (int i = 0; i < 40; ++i)
    clean += event(i, i % 2 ? "PLANT_TRUTH" : "CONTROL_COMMAND", std::string(i, 'a' + i % 26));
  int refused = 0, read_whole = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string bytes = clean;
    for (int k = 0; k < 1 + trial % 5; ++k) bytes[rng() % bytes.size()] = static_cast<char>(rng());
    const std::string path = write(bytes);
    try {
      long long event_bytes = 0;
      const logs::LogScan scan = logs::readLog(path, [&](const lcm::LogEvent& ev) {
        event_bytes += 28 + static_cast<long long>(ev.channel.size()) + ev.datalen;
      });
      EXPECT_EQ(event_bytes + scan.skipped_bytes + scan.unreadable_tail_bytes,
                static_cast<long long>(bytes.size()));
      ++read_whole;
    } catch (const logs::LogError& e) {
      EXPECT_NE(std::string(e.what()).find("malformed LCM log: the event at byte"), std::string::npos)
          << e.what();
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);  // the damage reached lengths sometimes
  EXPECT_GT(read_whole, 0);
}

}  // namespace
}  // namespace lagrange::tools
