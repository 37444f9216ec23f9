// The enum <-> name tables (util/enum_names.hpp): every table names each
// enumerator once and reads its names back; the choices a message lists.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "config/scenario.hpp"
#include "controller/paper_section.hpp"
#include "model/reference.hpp"
#include "transport/messages.hpp"
#include "transport/process_state.hpp"

namespace lagrange {
namespace {

// Each entry's name reads back to its value, and no name or value is listed twice.
template <class E, std::size_t N>
void expectRoundTrip(const util::EnumName<E> (&table)[N]) {
  std::set<std::string> names;
  std::set<E> values;
  for (const auto& entry : table) {
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name << " listed twice";
    EXPECT_TRUE(values.insert(entry.value).second) << entry.name << "'s value listed twice";
    EXPECT_EQ(util::enumFrom(table, entry.name), entry.value) << entry.name;
    EXPECT_STREQ(util::nameOf(table, entry.value), entry.name);
  }
  EXPECT_FALSE(util::enumFrom(table, "no such name").has_value());
}

TEST(EnumNames, EveryTableReadsBackWhatItWrites) {
  expectRoundTrip(config::kModeNames);
  expectRoundTrip(controller::kMotorRateNames);
  expectRoundTrip(config::kStaleTorqueNames);
  expectRoundTrip(model::kReferenceTypeNames);
  expectRoundTrip(transport::kProcessStateNames);
}

TEST(EnumNames, EveryEnumeratorHasAName) {
  // The last enumerator of each enum: a table that misses one fails here.
  EXPECT_EQ(std::size(config::kModeNames), static_cast<size_t>(config::Mode::kInproc) + 1);
  EXPECT_EQ(std::size(controller::kMotorRateNames),
            static_cast<size_t>(controller::MotorRate::kFiltered) + 1);
  EXPECT_EQ(std::size(config::kStaleTorqueNames), static_cast<size_t>(config::StaleTorque::kZero) + 1);
  EXPECT_EQ(std::size(model::kReferenceTypeNames),
            static_cast<size_t>(model::ReferenceType::kFreeMotion) + 1);
  EXPECT_EQ(std::size(transport::kProcessStateNames),
            static_cast<size_t>(transport::ProcessState::kFailed) + 1);
}

TEST(EnumNames, ChoicesReadAsAList) {
  EXPECT_EQ(util::choicesOf(config::kModeNames), "lockstep, realtime or inproc");
  EXPECT_EQ(util::choicesOf(config::kStaleTorqueNames), "zero or hold");
}

TEST(EnumNames, AStatusWithAnUnknownStateIsRejected) {
  lagrange::status_t m{};
  m.header = transport::makeHeader(0, 0.0);
  m.process = "plant";
  m.state = "finished";
  EXPECT_EQ(transport::validate(m), "");
  m.state = "done";
  EXPECT_EQ(transport::validate(m),
            "unknown state 'done'; expected ready, running, finished, interrupted or failed");
}

}  // namespace
}  // namespace lagrange
