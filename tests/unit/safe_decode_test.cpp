// safeDecode: a datagram that claims more elements than it carries is
// undecodable instead of a huge allocation (the finding of
// fuzz/message_fuzzer.cpp that made it), and honest messages still decode.
#include "transport/safe_decode.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "lagrange/control_command_t.hpp"
#include "lagrange/robot_description_t.hpp"
#include "lagrange/status_t.hpp"

namespace lagrange::transport {
namespace {

// A CONTROL_COMMAND of ~130 bytes whose num_joints and chain_order ask lcm-gen's
// decoder for about 10 GB (the fuzzer's out-of-memory input, selector byte dropped).
const std::vector<uint8_t> kTenGigabyteCommand = {
    0x87, 0x7b, 0x50, 0x6e, 0x0a, 0xfe, 0xf2, 0x3e, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01,
    0x3f, 0x50, 0x62, 0x4d, 0xd2, 0xf1, 0xa9, 0xfc, 0x00, 0x06, 0x60, 0xd6, 0xd8, 0x48, 0xe9, 0x50,
    0x78, 0x40, 0x23, 0xc4, 0xb9, 0x5a, 0x3a, 0xab, 0x00, 0x00, 0x00, 0x0b, 0x63, 0x6f, 0x6e, 0x74,
    0x72, 0x6f, 0x6c, 0x6c, 0x65, 0x72, 0x00, 0x00, 0x00, 0x1d, 0xcf, 0x00, 0x00, 0x00, 0xb4, 0x00,
    0x00, 0x00, 0x02, 0x00, 0x06, 0x40, 0x00, 0x01, 0x05, 0x47, 0x4b, 0x43, 0x74, 0xbf, 0xf8, 0x04,
    0x35, 0x11, 0x32, 0x21, 0x2c, 0x3f, 0x99, 0x83, 0xf6, 0x59, 0x96, 0x50, 0x00, 0xbf, 0xaa, 0x4b,
    0xab, 0x79, 0x4f, 0x50, 0x00, 0xc0, 0x59, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40, 0x52, 0xc0,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};

TEST(SafeDecode, ADatagramClaimingHugeArraysIsUndecodableNotAnAllocation) {
  lagrange::control_command_t m;
  EXPECT_FALSE(safeDecode(kTenGigabyteCommand.data(), kTenGigabyteCommand.size(), m));
  // Its budget: a few kilobytes, against the 10 GB its fields ask for.
  EXPECT_GT(decodeBudget(kTenGigabyteCommand.size()), 0u);
  EXPECT_LT(decodeBudget(kTenGigabyteCommand.size()), 64u * 1024u);
}

// A STATUS whose publisher string claims length INT_MIN (the fuzzer's second
// finding): lcm-gen's check let it through and `len - 1` overflowed; the
// generated headers are patched (lcmtypes/fix_string_decode.cmake).
const std::vector<uint8_t> kNegativeStringLength = {
    0x32, 0x04, 0x85, 0xb1, 0xa3, 0x71, 0x0f, 0x91, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x06, 0x60, 0xd6, 0xd8, 0x5e, 0x7b, 0xff, 0xff,
    0x60, 0x00, 0x00, 0x01, 0xe3, 0xf8, 0x80, 0x00, 0x00, 0x00, 0x06, 0x70, 0x6c, 0x61, 0x6e, 0x74, 0x00,
    0x00, 0x00, 0x1e, 0x19, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x70,
    0x6c, 0x61, 0x6e, 0x74, 0x00, 0x00, 0x00, 0x00, 0x06, 0x72, 0x65, 0x61, 0x64, 0x79, 0x00, 0xff, 0xff,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x7f, 0xf8, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x00, 0x5e, 0x00, 0x00, 0x00, 0x0f, 0x41, 0x43, 0x54, 0x55, 0x41, 0x54, 0x4f,
    0x52, 0x5f, 0x53, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x37, 0x00};

TEST(SafeDecode, ANegativeStringLengthIsUndecodable) {
  lagrange::status_t m;
  EXPECT_FALSE(safeDecode(kNegativeStringLength.data(), kNegativeStringLength.size(), m));
}

// The same in an element of a string array (robot_description_t's
// joint_names, the fuzzer's finding when the type was added): an honest
// message whose first joint name claims length INT_MIN. Under UBSan the
// unpatched `__elem_len - 1` aborts the test.
TEST(SafeDecode, ANegativeStringLengthInAStringArrayIsUndecodable) {
  lagrange::robot_description_t m{};
  m.kind = "planar_chain";
  m.num_joints = 1;
  m.joint_names = {"joint1"};
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  lagrange::robot_description_t back;
  ASSERT_TRUE(safeDecode(bytes.data(), bytes.size(), back));
  EXPECT_EQ(back.joint_names, m.joint_names);
  // fingerprint (8), kind's length (4) and bytes with NUL (13), num_joints (4):
  // then the first name's length, big-endian.
  const size_t at = 8 + 4 + m.kind.size() + 1 + 4;
  ASSERT_EQ(bytes[at + 3], m.joint_names[0].size() + 1);
  bytes[at] = 0x80;
  bytes[at + 1] = bytes[at + 2] = bytes[at + 3] = 0x00;
  EXPECT_FALSE(safeDecode(bytes.data(), bytes.size(), back));
}

TEST(SafeDecode, HonestMessagesDecodeWithinTheirBudget) {
  lagrange::control_command_t m{};
  m.num_joints = 7;
  m.chain_order = 4;
  for (auto* v : {&m.u, &m.q_desired, &m.q_error, &m.theta, &m.filter_state}) v->assign(7, 1.5);
  m.xi_error.assign(4, std::vector<double>(7, 2.5));
  m.header.publisher = "controller";
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  lagrange::control_command_t back;
  ASSERT_TRUE(safeDecode(bytes.data(), bytes.size(), back));
  EXPECT_EQ(back.xi_error, m.xi_error);
  EXPECT_EQ(back.header.publisher, "controller");
  bytes.pop_back();  // one byte short: not a whole message
  EXPECT_FALSE(safeDecode(bytes.data(), bytes.size(), back));
}

TEST(SafeDecode, TheBudgetEndsWithTheDecode) {
  {
    const AllocationBudget budget(16);
    EXPECT_THROW(std::vector<double>(100), std::bad_alloc);
  }
  EXPECT_NO_THROW(std::vector<double>(1000000));  // no budget outside
}

}  // namespace
}  // namespace lagrange::transport
