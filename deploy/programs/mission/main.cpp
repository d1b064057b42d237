// swa_mission: the ground's swarm mission, sent once over Fast DDS (or kept, --stay). See --help (mission_options.cpp).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>

#include <swa/msg/SwarmMissionPubSubTypes.h>

#include "mission_options.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/mission.h"

namespace swa::mission_tool {
namespace {

constexpr int kExitTooFewReaders = 3;
constexpr int kExitNotAcknowledged = 4;
constexpr auto kPoll = std::chrono::milliseconds(20);

class MissionSender : public app::Role {
 public:
  MissionSender(const MissionOptions& options, int domain, const std::string& profiles)
      : options_(options), participant_("swa_ground", domain, profiles) {
    writer_ = participant_.writer<msg::SwarmMissionPubSubType>(dds::topics::kMission, dds::qos::kMissionWriter);
  }

  int run() override {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.wait_s);
    while (writer_.matched() < options_.expect && std::chrono::steady_clock::now() < deadline) {
      if (waitFor(kPoll)) return 0;
    }
    const int readers = writer_.matched();
    if (readers < options_.expect) {
      std::fprintf(stderr, "swa_mission: %d reader(s) of %s matched in %.1f s, --expect %d: nothing sent\n", readers,
                   dds::topics::kMission, options_.wait_s, options_.expect);
      return kExitTooFewReaders;
    }
    const auto wall = std::chrono::system_clock::now().time_since_epoch();
    msg::SwarmMission m =
        wire::toMsg(options_.command, std::chrono::duration_cast<std::chrono::nanoseconds>(wall).count(), 1);
    if (!writer_.write(m)) {
      std::fprintf(stderr, "swa_mission: the middleware refused the mission\n");
      return 1;
    }
    const bool acknowledged = writer_.waitForAcknowledgments(options_.wait_s);
    std::fprintf(stderr, "swa_mission: %s sent to %d reader(s) of %s, %s\n",
                 options_.command.hold ? "a hold" : (std::to_string(options_.command.legs.size()) + " leg(s)").c_str(),
                 writer_.matched(), dds::topics::kMission,
                 acknowledged ? "acknowledged by every one" : "NOT acknowledged by every one in time");
    if (options_.stay) {
      std::fprintf(stderr, "swa_mission: staying, the ground's writer, until SIGINT or SIGTERM\n");
      while (!waitFor(std::chrono::seconds(1))) {
      }
    }
    return acknowledged ? 0 : kExitNotAcknowledged;
  }

  void stop() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
  }

 private:
  // True once stop() was called.
  bool waitFor(std::chrono::steady_clock::duration d) {
    std::unique_lock<std::mutex> lock(mutex_);
    return wake_.wait_for(lock, d, [this] { return stop_; });
  }

  MissionOptions options_;
  dds::Participant participant_;
  dds::Writer<msg::SwarmMission> writer_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
};

app::Plan prepare(const std::vector<std::string>& args) {
  const MissionOptions options = parseMissionOptions(args);
  if (auto done = app::printIf(options.help, missionUsage)) return *done;
  const int domain = dds::resolveDomain(options.domain);
  return app::startWith([options, domain]() -> std::unique_ptr<app::Role> {
    return std::make_unique<MissionSender>(options, domain, dds::resolveProfilesFile());
  });
}

}  // namespace
}  // namespace swa::mission_tool

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_mission", "mission", argc, argv, swa::mission_tool::prepare);
}
