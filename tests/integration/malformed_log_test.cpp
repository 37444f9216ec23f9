// A log whose event header lies about its lengths (0x7fffffff once crashed
// the log reader of replay, report and view with SIGSEGV): each command exits
// 2 and names the file, the event's byte offset and what was expected.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "support/configs.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

void putBigEndian32(std::string& bytes, std::size_t at, uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((v >> (8 * (3 - i))) & 0xff);
}

struct Crafted {
  std::string path;
  std::size_t offset;  // of the damaged event
};

// The golden log with one length field of event `index` overwritten:
// `field` 20 is the channel length, 24 the data length (LCM log format).
Crafted damaged(const std::string& tag, int index, std::size_t field, uint32_t value) {
  std::ifstream in(kGoldenRigidLockstep, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t offset = 0;
  for (int i = 0; i < index; ++i) {
    EXPECT_EQ(bigEndian32(bytes, offset), 0xEDA1DA01u) << "event " << i << " of " << kGoldenRigidLockstep;
    offset += 28 + bigEndian32(bytes, offset + 20) + bigEndian32(bytes, offset + 24);
  }
  EXPECT_EQ(bigEndian32(bytes, offset), 0xEDA1DA01u);
  putBigEndian32(bytes, offset + field, value);
  Crafted c{freshDir(tag) + ".lcm", offset};
  std::ofstream(c.path, std::ios::binary) << bytes;
  // The damage is in the file: the header now says what the test says it does.
  std::ifstream back(c.path, std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(back)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bigEndian32(written, offset + field), value);
  return c;
}

void expectRefusedByEveryCommand(const Crafted& log, const std::string& expected) {
  const std::string at = "the event at byte " + std::to_string(log.offset) + " ";
  const std::vector<std::string> commands = {
      "replay " + quote(log.path), "replay " + quote(log.path) + " --component plant",
      "report " + quote(log.path) + " -o " + quote(freshDir("malformed-report")),
      "view " + quote(log.path) + " --port 0"};
  for (const std::string& command : commands) {
    const RunResult r = lagrange(command);
    EXPECT_EQ(r.exit_code, 2) << command << ":\n" << r.output;  // -1 would be a signal
    EXPECT_NE(r.output.find(log.path + ": malformed LCM log: " + at), std::string::npos) << command << ":\n"
                                                                                         << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << command << ":\n" << r.output;
    EXPECT_EQ(r.output.find("http://"), std::string::npos) << command << ": nothing served:\n" << r.output;
  }
}

TEST(MalformedLog, AHugeDataLengthIsNamedWithItsOffsetByReplayReportAndView) {
  expectRefusedByEveryCommand(damaged("huge-data", 40, 24, 0x7fffffffu),
                              "gives a data length of 2147483647 bytes; expected 0 to 268435456");
}

TEST(MalformedLog, AHugeOrNegativeChannelLengthIsNamedWithItsOffsetByReplayReportAndView) {
  expectRefusedByEveryCommand(damaged("huge-channel", 7, 20, 0x7fffffffu),
                              "gives a channel name length of 2147483647 bytes; expected 1 to 999");
  expectRefusedByEveryCommand(damaged("negative-data", 3, 24, 0xfffffff0u),
                              "gives a data length of -16 bytes; expected 0 to 268435456");
}

// The first event is SCENARIO: damaged there, the log is refused, not taken for "no SCENARIO".
TEST(MalformedLog, ADamagedFirstEventIsNamedAsSuch) {
  const Crafted first = damaged("first-event", 0, 24, 0x80000000u);
  const RunResult r = lagrange("replay " + quote(first.path));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("malformed LCM log: the event at byte 0 gives a data length of -2147483648"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace lagrange::testing
