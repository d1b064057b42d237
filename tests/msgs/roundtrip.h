#pragma once
// Goes through the TopicDataType entry points a DataWriter/DataReader uses (size provider, serialize,
// deserialize), so the tests cover the wire path and not only the structs' own CDR methods. The mapping tests send
// core types through the wire bridge and this path and back.
#include <fastdds/rtps/common/SerializedPayload.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>

#include <swa/msg/MessageHeader.h>

namespace swa::msg::test {

inline MessageHeader make_header(int64_t stamp_ns, uint32_t seq) {
  MessageHeader h;
  h.stamp_ns(stamp_ns);
  h.seq(seq);
  return h;
}

// Returns the deserialised copy, or nullopt (with a recorded failure) if either direction failed.
template <class PubSubType, class Msg>
std::optional<Msg> round_trip(Msg in) {
  PubSubType type;
  const uint32_t predicted = type.getSerializedSizeProvider(&in)();
  eprosima::fastrtps::rtps::SerializedPayload_t payload(predicted);
  if (!type.serialize(&in, &payload)) {
    ADD_FAILURE() << "serialize failed into a payload of " << predicted << " bytes";
    return std::nullopt;
  }
  // A writer sizes its buffer from the provider: an under-estimate would fail at runtime.
  EXPECT_EQ(payload.length, predicted);
  Msg out;
  if (!type.deserialize(&payload, &out)) {
    ADD_FAILURE() << "deserialize failed";
    return std::nullopt;
  }
  return out;
}

// The message after the wire, which must equal what was sent; also checks the registered type name.
template <class PubSubType, class Msg>
Msg through_the_wire(const Msg& in, const char* type_name) {
  EXPECT_STREQ(PubSubType().getName(), type_name);
  const std::optional<Msg> out = round_trip<PubSubType>(in);
  if (!out) return Msg{};
  EXPECT_TRUE(*out == in) << type_name << ": the copy differs from the original";
  return *out;
}

}  // namespace swa::msg::test
