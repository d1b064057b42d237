// The endpoint side of participant.h (endpoints.h): matched counts, acknowledgments, sample identities to and from
// Fast DDS's types, and the raw listener. Apart from participant.cpp: nothing here creates or deletes an entity.

#include "swa/dds/endpoints.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include <fastdds/rtps/common/WriteParams.h>
#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace detail {

int publicationMatched(fdds::DataWriter* writer) {
  fdds::PublicationMatchedStatus status;
  if (writer == nullptr || writer->get_publication_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

int subscriptionMatched(fdds::DataReader* reader) {
  fdds::SubscriptionMatchedStatus status;
  if (reader == nullptr || reader->get_subscription_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

bool waitForAcknowledgments(fdds::DataWriter* writer, double seconds) {
  if (writer == nullptr) return false;
  return writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(seconds)) == ReturnCode_t::RETCODE_OK;
}

namespace {

Guid guidOf(const eprosima::fastrtps::rtps::GUID_t& g) {
  Guid out{};
  std::copy(g.guidPrefix.value, g.guidPrefix.value + 12, out.begin());
  std::copy(g.entityId.value, g.entityId.value + 4, out.begin() + 12);
  return out;
}

eprosima::fastrtps::rtps::GUID_t fastGuidOf(const Guid& g) {
  eprosima::fastrtps::rtps::GUID_t out;
  std::copy(g.begin(), g.begin() + 12, out.guidPrefix.value);
  std::copy(g.begin() + 12, g.end(), out.entityId.value);
  return out;
}

SampleId sampleIdOf(const eprosima::fastrtps::rtps::SampleIdentity& id) {
  return SampleId{guidOf(id.writer_guid()), static_cast<std::int64_t>(id.sequence_number().to64long())};
}

eprosima::fastrtps::rtps::SampleIdentity fastSampleIdOf(const SampleId& id) {
  eprosima::fastrtps::rtps::SampleIdentity out;
  out.writer_guid(fastGuidOf(id.writer));
  out.sequence_number(eprosima::fastrtps::rtps::SequenceNumber_t(static_cast<std::uint64_t>(id.seq)));
  return out;
}

}  // namespace

bool writeRelated(fdds::DataWriter* writer, void* data, const SampleId* related, const Guid* reply_reader,
                  SampleId* written) {
  if (writer == nullptr) return false;
  eprosima::fastrtps::rtps::WriteParams params;
  if (related != nullptr) params.related_sample_identity(fastSampleIdOf(*related));
  if (reply_reader != nullptr) params.related_sample_identity().writer_guid(fastGuidOf(*reply_reader));
  if (!writer->write(data, params)) return false;
  if (written != nullptr) *written = sampleIdOf(params.sample_identity());
  return true;
}

Guid readerGuid(const fdds::DataReader* reader) { return reader == nullptr ? Guid{} : guidOf(reader->guid()); }

SampleIds sampleIdsOf(const fdds::SampleInfo& info) {
  return SampleIds{sampleIdOf(info.sample_identity), sampleIdOf(info.related_sample_identity)};
}

void RawListener::on_data_available(fdds::DataReader* reader) {
  fdds::SampleInfo info;
  RawSample sample;
  while (reader->take_next_sample(&sample.payload, &info) == ReturnCode_t::RETCODE_OK) {
    if (info.valid_data) {
      sample.source_time_ns = info.source_timestamp.to_ns();
      sample.id = sampleIdOf(info.sample_identity);
      on_sample_(std::move(sample));
    }
    sample = RawSample();
  }
}

}  // namespace detail

}  // namespace swa::dds
