#pragma once
// The typed endpoint handles a Participant hands out (Writer / Reader), the identities of samples and writers, and
// the listeners that pass a reader's samples to its callback. Apart from participant.h: they are what a node uses
// once its endpoints exist, and none of it creates or deletes a DDS entity.

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "swa/dds/raw_type.h"

namespace swa::dds {

class Participant;

// The GUID of the writer a sample came from (its DDS publication handle).
using WriterGuid = std::array<std::uint8_t, 16>;
// An endpoint's GUID (a reader's too).
using Guid = WriterGuid;

// A sample's identity: its writer's GUID and its sequence number. A ROS 2 service over DDS pairs a reply with its
// request by it: the reply carries the request's identity as its "related" one.
struct SampleId {
  Guid writer{};
  std::int64_t seq = 0;
  bool operator==(const SampleId& o) const { return writer == o.writer && seq == o.seq; }
};
struct SampleIds {
  SampleId self, related;  // related: zero unless the writer named one (a reply names its request)
};

namespace detail {
int publicationMatched(eprosima::fastdds::dds::DataWriter* writer);
int subscriptionMatched(eprosima::fastdds::dds::DataReader* reader);
bool waitForAcknowledgments(eprosima::fastdds::dds::DataWriter* writer, double seconds);
// write() with the related sample identity set to `related` (a reply), or with only its writer GUID set to
// `reply_reader` (a request, as rmw_fastrtps sends one); the written sample's identity in `written`.
bool writeRelated(eprosima::fastdds::dds::DataWriter* writer, void* data, const SampleId* related,
                  const Guid* reply_reader, SampleId* written);
Guid readerGuid(const eprosima::fastdds::dds::DataReader* reader);
SampleIds sampleIdsOf(const eprosima::fastdds::dds::SampleInfo& info);

// A listener that also hands over the sample's identities (a service's request or reply).
template <class Msg>
class IdentityListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit IdentityListener(std::function<void(Msg&&, const SampleIds&)> on_sample)
      : on_sample_(std::move(on_sample)) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    eprosima::fastdds::dds::SampleInfo info;
    Msg msg;
    while (reader->take_next_sample(&msg, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) on_sample_(std::move(msg), sampleIdsOf(info));
      msg = Msg();
    }
  }

 private:
  std::function<void(Msg&&, const SampleIds&)> on_sample_;
};

template <class Msg>
class CallbackListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit CallbackListener(std::function<void(Msg&&, const WriterGuid&)> on_sample)
      : on_sample_(std::move(on_sample)) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    eprosima::fastdds::dds::SampleInfo info;
    Msg msg;
    while (reader->take_next_sample(&msg, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        WriterGuid writer{};
        const eprosima::fastrtps::rtps::octet* h = info.publication_handle.value;
        std::copy(h, h + writer.size(), writer.begin());
        on_sample_(std::move(msg), writer);
      }
      msg = Msg();
    }
  }

 private:
  std::function<void(Msg&&, const WriterGuid&)> on_sample_;
};
// One sample of a raw reader: its payload as it came off the wire, and when its writer sent it.
struct RawSample {
  Payload payload;
  std::int64_t source_time_ns = 0;  // the writer's clock (wall time since the epoch), 0 if not known
  SampleId id;                      // its writer and sequence number
};

class RawListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit RawListener(std::function<void(RawSample&&)> on_sample) : on_sample_(std::move(on_sample)) {}
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

 private:
  std::function<void(RawSample&&)> on_sample_;
};
}  // namespace detail

using detail::RawSample;

template <class Msg>
class Writer {
 public:
  Writer() = default;
  // False if the middleware refused the sample (e.g. serialisation failed).
  bool write(Msg& msg) { return writer_->write(&msg); }
  // Readers currently matched (discovery done both ways as seen from this writer).
  int matched() const { return detail::publicationMatched(writer_); }
  // A ROS 2 service request: written with the GUID of the reader that takes the replies; its identity, which the reply
  // will name, or nullopt if refused.
  std::optional<SampleId> writeRequest(Msg& msg, const Guid& reply_reader) {
    SampleId written;
    if (!detail::writeRelated(writer_, &msg, nullptr, &reply_reader, &written)) return std::nullopt;
    return written;
  }
  // A ROS 2 service reply to the request `request`.
  bool writeReply(Msg& msg, const SampleId& request) {
    return detail::writeRelated(writer_, &msg, &request, nullptr, nullptr);
  }
  // Blocks until every matched reliable reader acknowledged everything written, at most `seconds`.
  bool waitForAcknowledgments(double seconds) { return detail::waitForAcknowledgments(writer_, seconds); }
  explicit operator bool() const { return writer_ != nullptr; }

 private:
  friend class Participant;
  explicit Writer(eprosima::fastdds::dds::DataWriter* writer) : writer_(writer) {}
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

template <class Msg>
class Reader {
 public:
  Reader() = default;
  int matched() const { return detail::subscriptionMatched(reader_); }
  Guid guid() const { return detail::readerGuid(reader_); }
  explicit operator bool() const { return reader_ != nullptr; }

 private:
  friend class Participant;
  explicit Reader(eprosima::fastdds::dds::DataReader* reader) : reader_(reader) {}
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace swa::dds
