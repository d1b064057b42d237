// swa/uav<i>/state: the AgentState type survives the DDS serialisation path, and the agent's diagnostics go through
// the wire bridge (swa/wire/agent_state.h) and the wire and come back as the monitor reads them.

#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <swa/msg/AgentStatePubSubTypes.h>

#include "roundtrip.h"
#include "swa/wire/agent_state.h"

namespace swa::wire {
namespace {

using msg::test::make_header;
using msg::test::through_the_wire;

agent::Diagnostics everyFieldSet() {
  agent::Diagnostics d;
  d.stamp_ns = 12'000'000'000;
  d.mode = agent::Mode::kAnchored;
  d.stage = agent::Stage::kTracking;
  d.position_m = agent::Vec2(1.0 / 3.0, -2.5);
  d.velocity_mps = agent::Vec2(0.25, -0.75);
  d.position_cov_m2 << 0.11, 0.012, 0.012, 0.13;
  d.velocity_cov_m2ps2 << 0.021, 0.0022, 0.0022, 0.023;
  d.frame_valid = true;
  d.frame_centre_m = agent::Vec2(-4.5, 3.25);
  d.neighbour_count = 3;
  d.neighbour_ids = {};
  d.neighbour_ids[0] = 4;
  d.neighbour_ids[1] = 9;
  d.neighbour_ids[2] = 1;
  d.confirmed_tracks = 3;
  d.tentative_tracks = 1;
  d.rejected.nonfinite = 10;
  d.rejected.out_of_order = 11;
  d.rejected.oversize = 12;
  d.rejected.bad_id = 6;
  d.rejected.implausible = 14;
  d.rejected.no_heading = 5'000'000'015ULL;
  d.rejected.future = 16;
  d.stamp_resyncs = 17;
  d.commands = 77;
  d.gnss_valid = true;
  return d;
}

TEST(WireMessages, AgentStateSurvivesSerialisation) {
  // GIVEN a state with non-first enumerators and every other field distinct and non-default
  msg::AgentState in = toMsg(everyFieldSet(), 6, 1200);
  in.stage(msg::STAGE_LOST);
  // WHEN it goes through serialize/deserialize THEN the copy equals the original
  const msg::AgentState out = through_the_wire<msg::AgentStatePubSubType>(in, "swa::msg::AgentState");
  EXPECT_EQ(out.mode(), msg::MODE_ANCHORED);
  EXPECT_EQ(out.stage(), msg::STAGE_LOST);
  EXPECT_EQ(out.neighbour_ids(), (std::vector<std::int32_t>{4, 9, 1}));
  EXPECT_EQ(out.rejected_no_heading(), 5'000'000'015ULL);
}

// Pins a fastddsgen 2.3 property the publisher relies on knowing: sequence<int32, 64> is not checked on either side.
// If this starts failing, the generator began enforcing the bound.
TEST(WireMessages, GeneratedCodeDoesNotEnforceNeighbourIdsBound) {
  // GIVEN 65 neighbour ids, one over the IDL bound
  msg::AgentState in;
  in.neighbour_ids(std::vector<std::int32_t>(65, 3));
  // WHEN it goes through serialize/deserialize THEN all 65 arrive: truncating to 64 is the publisher's job
  EXPECT_EQ(through_the_wire<msg::AgentStatePubSubType>(in, "swa::msg::AgentState").neighbour_ids().size(), 65u);
}

TEST(WireAgentState, DiagnosticsSurviveTheBridgeAndTheWire) {
  // GIVEN an agent's diagnostics with every carried field set
  const agent::Diagnostics d = everyFieldSet();
  // WHEN they go diagnostics -> message -> wire -> message -> diagnostics
  const msg::AgentState m = through_the_wire<msg::AgentStatePubSubType>(toMsg(d, 3, 8), "swa::msg::AgentState");
  const AgentStateSample s = fromMsg(m);
  // THEN the message names the UAV and its sequence, and every carried field comes back bit for bit
  EXPECT_EQ(m.uav_id(), 3u);
  EXPECT_EQ(m.header().seq(), 8u);
  EXPECT_EQ(m.mode(), msg::MODE_ANCHORED);
  EXPECT_EQ(m.stage(), msg::STAGE_TRACKING);
  EXPECT_EQ(s.uav, 3);
  EXPECT_EQ(s.mode, agent::Mode::kAnchored);
  EXPECT_EQ(s.stage, agent::Stage::kTracking);
  EXPECT_FALSE(s.no_input);
  const agent::Diagnostics& r = s.diagnostics;
  EXPECT_EQ(r.stamp_ns, d.stamp_ns);
  EXPECT_EQ(r.position_m, d.position_m);
  EXPECT_EQ(r.velocity_mps, d.velocity_mps);
  EXPECT_EQ(r.position_cov_m2, d.position_cov_m2);
  EXPECT_EQ(r.velocity_cov_m2ps2, d.velocity_cov_m2ps2);
  EXPECT_EQ(r.frame_valid, d.frame_valid);
  EXPECT_EQ(r.frame_centre_m, d.frame_centre_m);
  EXPECT_EQ(r.neighbour_count, d.neighbour_count);
  EXPECT_EQ(r.neighbour_ids, d.neighbour_ids);
  EXPECT_EQ(r.confirmed_tracks, d.confirmed_tracks);
  EXPECT_EQ(r.tentative_tracks, d.tentative_tracks);
  EXPECT_EQ(r.rejected.nonfinite, d.rejected.nonfinite);
  EXPECT_EQ(r.rejected.out_of_order, d.rejected.out_of_order);
  EXPECT_EQ(r.rejected.oversize, d.rejected.oversize);
  EXPECT_EQ(r.rejected.bad_id, d.rejected.bad_id);
  EXPECT_EQ(r.rejected.implausible, d.rejected.implausible);
  EXPECT_EQ(r.rejected.no_heading, d.rejected.no_heading);
  EXPECT_EQ(r.rejected.future, d.rejected.future);
  EXPECT_EQ(r.stamp_resyncs, d.stamp_resyncs);
  EXPECT_EQ(r.commands, d.commands);
  EXPECT_EQ(r.gnss_valid, d.gnss_valid);
}

TEST(WireAgentState, TheGnssFlagOfMessageSet4IsTheLastByteSoASet3StateIsRefusedNotMisread) {
  // GIVEN a set-4 state of an agent without GNSS, serialised as a DataWriter does
  agent::Diagnostics d = everyFieldSet();
  d.gnss_valid = false;
  msg::AgentState m = toMsg(d, 3, 8);
  msg::AgentStatePubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  ASSERT_TRUE(type.serialize(&m, &p));
  // THEN gnss_valid is the body's last byte, after commands_sent: set 3's fields keep their offsets
  ASSERT_GT(p.length, 4u + 9u);
  EXPECT_EQ(p.data[p.length - 1], 0u);
  std::uint64_t commands = 0;
  std::memcpy(&commands, p.data + p.length - 9, sizeof commands);
  EXPECT_EQ(commands, 77u);
  // AND a set-3 agent's state (the same bytes without it) is refused, never read as "no GNSS": a set-4 bridge feeds
  // nothing from an agent it cannot read (deploy/README.md, message set 4)
  eprosima::fastrtps::rtps::SerializedPayload_t set3(p.length - 1);
  std::memcpy(set3.data, p.data, p.length - 1);
  set3.length = p.length - 1;
  msg::AgentState out;
  EXPECT_FALSE(type.deserialize(&set3, &out));
}

TEST(WireAgentState, MoreNeighboursThanTheArrayAreCutNeverReadPastIt) {
  // GIVEN diagnostics claiming more neighbours than they hold (a corrupt count)
  agent::Diagnostics d = everyFieldSet();
  d.neighbour_count = 1000;
  // WHEN published THEN the ids are cut to what the array and the IDL bound hold
  EXPECT_EQ(toMsg(d, 3, 9).neighbour_ids().size(),
            std::min<std::size_t>(d.neighbour_ids.size(), kMaxStateNeighbourIds));
}

TEST(WireAgentState, ValuesOffTheWireAreNotTrusted) {
  // GIVEN states with values no agent of this build sends
  msg::AgentState m = toMsg(everyFieldSet(), 0, 1);
  m.uav_id(std::numeric_limits<std::uint32_t>::max());
  m.mode(static_cast<msg::AgentMode>(7));
  m.stage(static_cast<msg::AgentStage>(9));
  m.neighbour_ids(std::vector<std::int32_t>(500, 2));
  // WHEN read
  const AgentStateSample s = fromMsg(m);
  // THEN the id is no UAV's, unknown enums are unknown (and never scored), and the neighbour count is kept
  EXPECT_EQ(s.uav, -1);
  EXPECT_FALSE(s.mode.has_value());
  EXPECT_FALSE(s.stage.has_value());
  EXPECT_EQ(s.diagnostics.mode, agent::Mode::kStandalone);
  EXPECT_EQ(s.diagnostics.stage, agent::Stage::kInitializing);
  EXPECT_EQ(s.diagnostics.neighbour_count, 500);
  // AND STAGE_NO_INPUT reads as not tracking
  m.stage(msg::STAGE_NO_INPUT);
  EXPECT_EQ(fromMsg(m).stage, agent::Stage::kLost);
  EXPECT_TRUE(fromMsg(m).no_input);
}

}  // namespace
}  // namespace swa::wire
