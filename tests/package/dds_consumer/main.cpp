// Links swa::dds from an install: names the profiles the package gives and the topic of UAV 3's commands; with
// --domain D it makes a participant there with those profiles and a command writer, as an agent does.
#include <cstdio>
#include <string>

#include <swa/dds/participant.h>
#include <swa/dds/qos_profiles.h>
#include <swa/dds/topics.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

int main(int argc, char** argv) {
  std::printf("profiles %s\n", SWA_PROFILES_FILE);
  std::printf("topic %s\n", swa::dds::topics::cmdVel(3).c_str());
  if (argc == 3 && std::string(argv[1]) == "--domain") {
    swa::dds::Participant participant("swa_dds_consumer", std::stoi(argv[2]), SWA_PROFILES_FILE);
    auto writer = participant.writer<swa::msg::VelocitySetpointPubSubType>(swa::dds::topics::cmdVel(3),
                                                                           swa::dds::qos::kCommandWriter);
    std::printf("participant up, writer matched %d\n", writer.matched());
  }
  return 0;
}
