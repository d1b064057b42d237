#pragma once
// A TopicDataType whose sample is the serialized payload itself (CDR encapsulation header included), registered under
// any type name: what a recording keeps (the bytes exactly as they came off the wire) and what a replay sends back.
// A reader of it matches the writers of the type it is named after; the monitor decodes the bytes itself with the
// generated PubSubType (decodePayload) when it also needs the message.

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

namespace swa::dds {

using Payload = std::vector<std::uint8_t>;

class RawType : public eprosima::fastdds::dds::TopicDataType {
 public:
  // `max_size`: the largest payload accepted, as the generated type of `type_name` announces it (its m_typeSize), so
  // a raw reader preallocates what a typed one would.
  RawType(const std::string& type_name, std::uint32_t max_size) {
    setName(type_name.c_str());
    m_typeSize = max_size;
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const Payload& b = *static_cast<Payload*>(data);
    if (b.size() > payload->max_size) return false;
    std::memcpy(payload->data, b.data(), b.size());
    payload->length = static_cast<std::uint32_t>(b.size());
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    static_cast<Payload*>(data)->assign(payload->data, payload->data + payload->length);
    return true;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] { return static_cast<std::uint32_t>(static_cast<Payload*>(data)->size()); };
  }
  void* createData() override { return new Payload(); }
  void deleteData(void* data) override { delete static_cast<Payload*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

// The RawType standing in for the generated PubSubType: same name, same size.
template <class PubSubType>
RawType* rawTypeOf() {
  PubSubType generated;
  return new RawType(generated.getName(), generated.m_typeSize);
}

// `payload` decoded by the generated code of PubSubType; false if it does not decode (dropped by the caller).
template <class PubSubType>
bool decodePayload(const Payload& payload, typename PubSubType::type& out) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(static_cast<std::uint32_t>(payload.size()));
  std::memcpy(p.data, payload.data(), payload.size());
  p.length = static_cast<std::uint32_t>(payload.size());
  try {
    return type.deserialize(&p, &out);
  } catch (...) {  // fastcdr throws NotEnoughMemoryException on a short payload
    return false;
  }
}

// `payload` as today's PubSubType, also when it was written by an earlier message set whose type has since grown
// by fields appended at its end (Imu in set 5): a payload of exactly `earlier_bytes` (the earlier layout's size,
// encapsulation included) has its missing tail read as zeros (false, 0) and is re-encoded at today's size. Anything
// else is returned as it is (what does not decode is then dropped by its reader).
template <class PubSubType>
Payload upgradeAppended(const Payload& payload, std::size_t earlier_bytes);

// The bytes a DataWriter of PubSubType sends for `m` (CDR encapsulation header included); empty if it cannot.
template <class PubSubType>
Payload encodePayload(typename PubSubType::type m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  if (!type.serialize(&m, &p)) return {};
  return Payload(p.data, p.data + p.length);
}

template <class PubSubType>
Payload upgradeAppended(const Payload& payload, std::size_t earlier_bytes) {
  typename PubSubType::type m;
  PubSubType type;
  if (payload.size() != earlier_bytes || payload.size() >= type.m_typeSize) return payload;
  if (decodePayload<PubSubType>(payload, m)) return payload;
  Payload padded = payload;
  padded.resize(type.m_typeSize, 0);
  if (!decodePayload<PubSubType>(padded, m)) return payload;
  Payload upgraded = encodePayload<PubSubType>(m);
  return upgraded.empty() ? payload : upgraded;
}

}  // namespace swa::dds
