// The baseline of issue #24: what receiving the topics of a complete recording costs a bare Fast DDS reader. It joins
// the swarm like swa_monitor (same participant code, profiles file, SWA_SWARM partition, domain) and creates a raw
// reader of every topic `swa_monitor --record` records, with the monitor's own reader profiles
// (forEachRecordedTopic, recording_taps.h), and only counts the samples: no decoding, no metrics, no file. Started
// before the run, stopped with SIGTERM/SIGINT after it; then prints its own CPU time (getrusage) and the count per
// topic as one JSON object on stdout. Not a ctest: tests/bench/bench_record_live.sh runs it beside the monitor.
//
//   bench_record_reader --uav-count N [--domain D]          (SWA_SWARM, SWA_TRANSPORT, ... as for every SWA program)
//   bench_record_reader --count-mcap FILE.mcap              the messages per channel of a recording, same JSON shape
//   bench_record_reader --stamps-per-second FILE.mcap...    per channel and whole second of the samples' own stamps,
//                                                           how many distinct stamps the recordings hold together
//                                                           (a restarted monitor's files overlap; tests/soak)
//
// Topics are named as the recording names its channels (recordedTopic), so the two outputs compare key by key.

#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "recording_taps.h"
#include "swa/app/signals.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/recording/mcap_reader.h"

namespace {

using Counts = std::map<std::string, std::unique_ptr<std::atomic<std::uint64_t>>>;

struct CountInto {
  swa::dds::Participant& participant;
  Counts& counts;
  std::vector<swa::dds::Reader<swa::dds::Payload>>& readers;

  template <class PubSubType>
  void operator()(const std::string& topic, const char* profile) {
    auto& n = counts[swa::recording::recordedTopic(participant.wireNames(), topic)];
    n = std::make_unique<std::atomic<std::uint64_t>>(0);
    std::atomic<std::uint64_t>* counter = n.get();
    readers.push_back(participant.rawReader<PubSubType>(
        topic, profile, [counter](swa::dds::RawSample&&) { counter->fetch_add(1, std::memory_order_relaxed); }));
  }
};

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); }

int countMcap(const std::string& path) {
  swa::recording::McapReader reader(path);
  std::map<std::uint16_t, std::uint64_t> per_channel;
  while (const auto m = reader.next()) ++per_channel[m->channel_id];
  nlohmann::ordered_json counts = nlohmann::ordered_json::object();
  for (const auto& [id, channel] : reader.channels()) counts[channel.topic] = per_channel[id];
  std::printf(
      "%s\n",
      nlohmann::ordered_json{{"file", path}, {"truncated", reader.truncated()}, {"counts", counts}}.dump().c_str());
  return 0;
}

// The samples' own stamps (the recording's log time: a sensor sample's stamp, or its publication time) are simulated
// time, so a second here is a second of the run, whatever the recording monitor did meanwhile.
int stampsPerSecond(const std::vector<std::string>& paths) {
  std::map<std::string, std::set<std::uint64_t>> stamps;
  nlohmann::ordered_json truncated = nlohmann::ordered_json::array();
  for (const std::string& path : paths) {
    swa::recording::McapReader reader(path);
    while (const auto m = reader.next()) stamps[reader.channels().at(m->channel_id).topic].insert(m->log_time_ns);
    if (reader.truncated()) truncated.push_back(path);
  }
  nlohmann::ordered_json per_topic = nlohmann::ordered_json::object();
  for (const auto& [topic, set] : stamps) {
    std::map<std::uint64_t, std::uint64_t> per_second;
    for (const std::uint64_t t : set) ++per_second[t / 1'000'000'000ULL];
    nlohmann::ordered_json seconds = nlohmann::ordered_json::object();
    for (const auto& [second, n] : per_second) seconds[std::to_string(second)] = n;
    per_topic[topic] = seconds;
  }
  std::printf("%s\n",
              nlohmann::ordered_json{{"files", paths}, {"truncated", truncated}, {"stamps_per_second", per_topic}}
                  .dump()
                  .c_str());
  return 0;
}

int readRun(int uav_count, const std::optional<std::string>& domain) {
  swa::app::installShutdownHandlers();
  Counts counts;
  std::vector<swa::dds::Reader<swa::dds::Payload>> readers;
  {
    swa::dds::Participant participant("swa_bench_reader", swa::dds::resolveDomain(domain),
                                      swa::dds::resolveProfilesFile());
    swa::recording::forEachRecordedTopic(uav_count, CountInto{participant, counts, readers});
    swa::app::acceptShutdownSignals();
    std::fprintf(stderr, "bench_record_reader: %zu readers\n", readers.size());
    while (!swa::app::shutdownRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    readers.clear();
  }  // the participant and its readers deleted: the CPU time below includes their teardown, like the monitor's
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  nlohmann::ordered_json out;
  out["cpu_s"] = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  out["user_s"] = seconds(usage.ru_utime);
  out["system_s"] = seconds(usage.ru_stime);
  nlohmann::ordered_json per_topic = nlohmann::ordered_json::object();
  for (const auto& [topic, n] : counts) per_topic[topic] = n->load();
  out["counts"] = per_topic;
  std::printf("%s\n", out.dump().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 2 && args[0] == "--count-mcap") return countMcap(args[1]);
    if (args.size() >= 2 && args[0] == "--stamps-per-second") return stampsPerSecond({args.begin() + 1, args.end()});
    int uav_count = -1;
    std::optional<std::string> domain;
    for (std::size_t k = 0; k + 1 < args.size(); k += 2) {
      if (args[k] == "--uav-count")
        uav_count = std::stoi(args[k + 1]);
      else if (args[k] == "--domain")
        domain = args[k + 1];
      else
        uav_count = -1, k = args.size();
    }
    if (uav_count < 1 || args.size() % 2 != 0) {
      std::fprintf(stderr,
                   "usage: bench_record_reader --uav-count N [--domain D] | --count-mcap FILE.mcap\n"
                   "       | --stamps-per-second FILE.mcap...\n"
                   "  (see the comment at the top of tests/bench/bench_record_reader.cpp)\n");
      return 2;
    }
    return readRun(uav_count, domain);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_record_reader: %s\n", e.what());
    return 2;
  }
}
