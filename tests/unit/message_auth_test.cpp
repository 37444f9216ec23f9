// Authenticated messages (transport/message_auth.hpp, LcmNode::authenticate)
// and the key file (runtime/key_file.hpp): a datagram is accepted only with
// the MAC of its exact bytes under the run's key; every other is dropped
// before decoding and counted; a key file is read only when it is private.
#include "transport/message_auth.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "lagrange/plant_position_t.hpp"
#include "runtime/key_file.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"

namespace lagrange::transport {
namespace {

MessageKey keyOf(uint8_t fill) {
  MessageKey k;
  k.fill(fill);
  return k;
}

TEST(MessageAuth, AnyChangedByteOrAnotherKeyFailsTheCheck) {
  const MessageAuthenticator auth(keyOf(7));
  std::vector<uint8_t> datagram = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  auth.sign(datagram);
  ASSERT_EQ(datagram.size(), 9 + kMacBytes);
  EXPECT_TRUE(auth.verify(datagram.data(), datagram.size()));
  for (size_t i = 0; i < datagram.size(); ++i) {  // payload and trailer alike
    std::vector<uint8_t> altered = datagram;
    altered[i] ^= 0x01;
    EXPECT_FALSE(auth.verify(altered.data(), altered.size())) << "byte " << i;
  }
  EXPECT_FALSE(MessageAuthenticator(keyOf(8)).verify(datagram.data(), datagram.size()));
  EXPECT_FALSE(auth.verify(datagram.data(), datagram.size() - 1));  // truncated
  EXPECT_FALSE(auth.verify(datagram.data(), kMacBytes - 1));        // shorter than a MAC
  std::vector<uint8_t> longer = datagram;
  longer.push_back(0);
  EXPECT_FALSE(auth.verify(longer.data(), longer.size()));
}

// RFC 4231, test case 2: the MAC is standard HMAC-SHA256, which Python's hmac
// and Java's javax.crypto compute the same way (docs/external_programs.md).
TEST(MessageAuth, IsStandardHmacSha256) {
  MessageKey key{};
  const std::string jefe = "Jefe";
  std::copy(jefe.begin(), jefe.end(), key.begin());
  // HMAC pads a short key with zeros to the block: "Jefe" and "Jefe" + 28 zero bytes are one key.
  const std::string text = "what do ya want for nothing?";
  // After another message: each MAC starts afresh from the key (the context is reused).
  const MessageAuthenticator auth(key);
  const std::string before = "another message, signed first";
  auth.mac(reinterpret_cast<const uint8_t*>(before.data()), before.size());
  const auto mac = auth.mac(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  std::string hex;
  for (const uint8_t b : mac) {
    static const char* digits = "0123456789abcdef";
    hex += digits[b >> 4];
    hex += digits[b & 15];
  }
  EXPECT_EQ(hex, "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

TEST(MessageAuth, KeysAreRandomAndRoundTripAsHex) {
  const MessageKey a = randomMessageKey(), b = randomMessageKey();
  EXPECT_NE(a, b);
  MessageKey back{};
  ASSERT_TRUE(fromHex(toHex(a), back));
  EXPECT_EQ(back, a);
  EXPECT_EQ(toHex(a).size(), 64u);
  EXPECT_FALSE(fromHex(toHex(a).substr(1), back));
  EXPECT_FALSE(fromHex(toHex(a) + "0", back));
  EXPECT_FALSE(fromHex(std::string(64, 'g'), back));
}

lagrange::plant_position_t position(int64_t tick) {
  lagrange::plant_position_t m;
  m.header = makeHeader(tick, 0.001 * static_cast<double>(tick));
  m.num_joints = 2;
  m.q = {0.1, 0.2};
  return m;
}

// In one process over LCM's in-memory provider: what the node signs reaches
// its handler; a datagram without the MAC, with another key's, or altered is
// counted as unauthenticated and never reaches it.
TEST(MessageAuth, ANodeWithAKeyAcceptsOnlyItsOwnSignedMessages) {
  LcmNode node("plant", "memq://", 42);
  node.authenticate(keyOf(1));
  std::vector<int64_t> ticks;
  node.subscribe<lagrange::plant_position_t>(
      kPlantPosition, [](const auto& m) { return validate(m, 2); },
      [&](const lagrange::plant_position_t& m) { ticks.push_back(m.header.tick); });

  node.publish(kPlantPosition, position(1));
  // A forger with the run id but not the key: the stamped, checksummed message, no MAC.
  lagrange::plant_position_t forged = position(2);
  forged.header.run_id = 42;
  forged.header.publisher = "plant";
  forged.header.publisher_pid = 1;
  forged.header.seq = 1000;
  seal(forged);
  std::vector<uint8_t> bytes(static_cast<size_t>(forged.getEncodedSize()));
  forged.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  node.raw().publish(kPlantPosition, bytes.data(), static_cast<unsigned>(bytes.size()));
  // The same with a MAC under another key, and a signed one altered in flight.
  std::vector<uint8_t> other_key = bytes;
  MessageAuthenticator(keyOf(2)).sign(other_key);
  node.raw().publish(kPlantPosition, other_key.data(), static_cast<unsigned>(other_key.size()));
  std::vector<uint8_t> altered = bytes;
  MessageAuthenticator(keyOf(1)).sign(altered);
  altered[20] ^= 0x40;
  node.raw().publish(kPlantPosition, altered.data(), static_cast<unsigned>(altered.size()));
  // And a correctly signed one (as the real publisher would send): accepted.
  std::vector<uint8_t> signed_bytes = bytes;
  MessageAuthenticator(keyOf(1)).sign(signed_bytes);
  node.raw().publish(kPlantPosition, signed_bytes.data(), static_cast<unsigned>(signed_bytes.size()));
  // Replayed: authentic, but its sequence number was seen.
  node.raw().publish(kPlantPosition, signed_bytes.data(), static_cast<unsigned>(signed_bytes.size()));
  while (node.drain() > 0) {
  }
  EXPECT_EQ(ticks, (std::vector<int64_t>{1, 2}));
  const ChannelCounters& c = node.counters().at(kPlantPosition);
  EXPECT_EQ(c.rejected_by[static_cast<size_t>(RejectReason::kUnauthenticated)], 3);
  EXPECT_EQ(c.rejected_by[static_cast<size_t>(RejectReason::kOldOrRepeated)], 1);
  EXPECT_EQ(c.received, 2);
  bool reported = false;
  for (const auto& s : node.channelStats())
    if (s.channel == kPlantPosition) reported = s.rejected_unauthenticated == 3;
  EXPECT_TRUE(reported);
}

// Every handler of a node sees the payload without the trailer, the raw ones too.
TEST(MessageAuth, RawHandlersSeeThePayloadOnlyAndEachForgeryIsCountedOnce) {
  LcmNode node("plant", "memq://", 42);
  node.authenticate(keyOf(3));
  std::vector<size_t> sizes;
  node.subscribeRaw(kPlantPosition, [&](const lcm::ReceiveBuffer* rbuf, const std::string&) {
    sizes.push_back(rbuf->data_size);
  });
  int typed = 0;
  node.subscribe<lagrange::plant_position_t>(
      kPlantPosition, [](const auto&) { return Rejection(); }, [&](const auto&) { ++typed; });
  const lagrange::plant_position_t m = position(3);
  node.publish(kPlantPosition, m);
  std::vector<uint8_t> junk(100, 0xab);
  node.raw().publish(kPlantPosition, junk.data(), static_cast<unsigned>(junk.size()));
  while (node.drain() > 0) {
  }
  lagrange::plant_position_t stamped = m;  // as published: only the publisher's name changes the size
  stamped.header.publisher = "plant";
  ASSERT_EQ(sizes.size(), 1u);
  EXPECT_EQ(sizes[0], static_cast<size_t>(stamped.getEncodedSize()));
  EXPECT_EQ(typed, 1);
  EXPECT_EQ(
      node.counters().at(kPlantPosition).rejected_by[static_cast<size_t>(RejectReason::kUnauthenticated)], 1);
}

// `m` as the plant of run 42 (pid 9) sends it with sequence number `seq`,
// sealed and signed, handled by `node` at once.
void sendAsPlant(LcmNode& node, const MessageAuthenticator& key, lagrange::plant_position_t m, int64_t seq) {
  m.header.run_id = 42;
  m.header.publisher = "plant";
  m.header.publisher_pid = 9;
  m.header.seq = seq;
  seal(m);
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  key.sign(bytes);
  node.raw().publish(kPlantPosition, bytes.data(), static_cast<unsigned>(bytes.size()));
  while (node.drain() > 0) {
  }
}

// Records (Order::kAcceptReordered) take a sequence number once, in any order,
// within a window of the publisher's newest; older is a replay.
TEST(MessageAuth, ReorderedRecordsCountOnceAndNothingOlderThanTheWindow) {
  LcmNode node("logger", "memq://", 42);
  node.authenticate(keyOf(5));
  std::vector<int64_t> seqs;
  node.subscribe<lagrange::plant_position_t>(
      kPlantPosition, [](const auto&) { return Rejection(); },
      [&](const lagrange::plant_position_t& m) { seqs.push_back(m.header.seq); },
      LcmNode::Order::kAcceptReordered);
  const MessageAuthenticator key(keyOf(5));
  auto send = [&](int64_t seq) { sendAsPlant(node, key, position(1), seq); };
  const int64_t w = HeaderAdmission::kSequenceWindow;
  for (const int64_t seq : {int64_t{5}, 3 * w, 2 * w + 1, 3 * w, 2 * w, int64_t{5}, 3 * w - 1}) send(seq);
  EXPECT_EQ(seqs, (std::vector<int64_t>{5, 3 * w, 2 * w + 1, 3 * w - 1}));
  EXPECT_EQ(node.counters().at(kPlantPosition).rejected_by[static_cast<size_t>(RejectReason::kOldOrRepeated)],
            3);
}

// Issue #44: a holder of the key sends a position far larger than any of
// the run's can be (its MAC valid, its checksum intact): a node bounded by
// the run's shape rejects it unread, as undecodable, and still takes the
// honest one. (The decoders would allocate up to 64 bytes per byte.)
TEST(MessageAuth, ADatagramLargerThanAnyOfTheRunsIsRejectedBeforeDecoding) {
  LcmNode node("controller", "memq://", 42);
  node.authenticate(keyOf(5));
  node.boundMessages({2, 0, 1, 4});
  int handled = 0;
  node.subscribe<lagrange::plant_position_t>(
      kPlantPosition, [](const auto&) { return Rejection(); }, [&](const auto&) { ++handled; });
  const MessageAuthenticator key(keyOf(5));
  auto send = [&](const lagrange::plant_position_t& m, int64_t seq) { sendAsPlant(node, key, m, seq); };
  lagrange::plant_position_t huge = position(1);
  huge.num_joints = 100000;
  huge.q.assign(100000, 0.5);
  EXPECT_TRUE(node.oversized(kPlantPosition, static_cast<size_t>(huge.getEncodedSize())));
  send(huge, 1);
  EXPECT_EQ(handled, 0);
  EXPECT_EQ(node.counters().at(kPlantPosition).rejected_by[static_cast<size_t>(RejectReason::kUndecodable)],
            1);
  send(position(2), 2);
  EXPECT_EQ(handled, 1);
  EXPECT_FALSE(node.oversized("SOMEONE_ELSES", 1u << 30));  // not a per-tick channel: not bounded here
}

class KeyFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("lagrange-key-test-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string errorOf(const std::string& file) const {
    try {
      runtime::readKeyFile(file);
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(KeyFile, IsWrittenPrivateAndReadBack) {
  const MessageKey key = randomMessageKey();
  runtime::writeKeyFile(path("run.key"), key);
  struct stat st {};
  ASSERT_EQ(stat(path("run.key").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(runtime::readKeyFile(path("run.key")), key);
  // Never overwritten, never through a link.
  EXPECT_THROW(runtime::writeKeyFile(path("run.key"), key), config::ConfigError);
  std::ofstream(path("target")) << "user data\n";
  std::filesystem::create_symlink(path("target"), path("link.key"));
  EXPECT_THROW(runtime::writeKeyFile(path("link.key"), key), config::ConfigError);
  std::ifstream in(path("target"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "user data");
}

TEST_F(KeyFile, RefusesWhatIsNotAPrivateKeyFileNamingTheFile) {
  EXPECT_NE(errorOf(path("missing")).find("missing"), std::string::npos);
  EXPECT_NE(errorOf(dir_.string()).find("not a regular file"), std::string::npos);

  const std::string open_to_all = path("open.key");
  std::ofstream(open_to_all) << toHex(randomMessageKey()) << "\n";
  chmod(open_to_all.c_str(), 0644);
  const std::string why = errorOf(open_to_all);
  EXPECT_NE(why.find("open.key"), std::string::npos) << why;
  EXPECT_NE(why.find("mode 644"), std::string::npos) << why;

  const std::string short_key = path("short.key");
  std::ofstream(short_key) << "abcd\n";
  chmod(short_key.c_str(), 0600);
  EXPECT_NE(errorOf(short_key).find("64 hex digits"), std::string::npos);

  const std::string huge = path("huge.key");
  std::ofstream(huge) << std::string(100000, 'a');
  chmod(huge.c_str(), 0600);
  EXPECT_NE(errorOf(huge).find("100000 bytes"), std::string::npos);

  EXPECT_NE(errorOf("/dev/zero").find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace lagrange::transport
