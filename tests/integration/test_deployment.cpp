// How a process joins DDS (swa/dds/deployment.h) and the launcher options that set it: pure parsing, no DDS traffic.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "error_text.h"
#include "fake_env.h"
#include "launch_options.h"
#include "scratch.h"
#include "swa/dds/deployment.h"
#include "swa/dds/qos_profiles.h"

namespace swa {
namespace {

dds::EnvLookup envOf(const std::map<std::string, std::string>& vars) { return testing::fakeEnv(vars); }

std::string errorOf(const std::map<std::string, std::string>& vars) {
  return testing::invalidArgumentText([&] { dds::parseDeployment(envOf(vars)); });
}

TEST(Deployment, DefaultsToLocalWithoutSecurity) {
  // WHEN no deployment variable is set
  const dds::Deployment d = dds::parseDeployment(envOf({}));
  // THEN a process joins over the local transport with the local participant profile, without security
  EXPECT_EQ(d.transport, dds::Transport::kLocal);
  EXPECT_TRUE(d.security_dir.empty());
  EXPECT_STREQ(dds::participantProfile(d.transport), dds::qos::kParticipant);
  // AND an empty SWA_TRANSPORT means the same
  EXPECT_EQ(dds::parseDeployment(envOf({{"SWA_TRANSPORT", ""}})).transport, dds::Transport::kLocal);
}

TEST(Deployment, EachTransportSelectsItsProfile) {
  // WHEN SWA_TRANSPORT is network THEN the network transport is used
  EXPECT_EQ(dds::parseDeployment(envOf({{"SWA_TRANSPORT", "network"}})).transport, dds::Transport::kNetwork);
  // WHEN it is discovery-server with a list of servers THEN that transport and those servers are used
  const dds::Deployment ds = dds::parseDeployment(
      envOf({{"SWA_TRANSPORT", "discovery-server"}, {"SWA_DISCOVERY_SERVER", "10.1.0.1:11811;10.1.0.2:11812"}}));
  EXPECT_EQ(ds.transport, dds::Transport::kDiscoveryServer);
  EXPECT_EQ(ds.discovery_servers, "10.1.0.1:11811;10.1.0.2:11812");
  // AND both network transports use the network participant profile
  EXPECT_STREQ(dds::participantProfile(dds::Transport::kNetwork), dds::qos::kParticipantNetwork);
  EXPECT_STREQ(dds::participantProfile(dds::Transport::kDiscoveryServer), dds::qos::kParticipantNetwork);
  // AND every transport's name parses back to it
  for (const auto t : {dds::Transport::kLocal, dds::Transport::kNetwork, dds::Transport::kDiscoveryServer}) {
    EXPECT_EQ(dds::parseTransport(dds::transportName(t)), t);
  }
}

TEST(Deployment, BadCombinationsNameTheVariable) {
  // WHEN the transport is unknown, or discovery-server without a valid server list THEN the error names the variable
  EXPECT_NE(errorOf({{"SWA_TRANSPORT", "shm"}}).find("SWA_TRANSPORT 'shm'"), std::string::npos);
  EXPECT_NE(errorOf({{"SWA_TRANSPORT", "discovery-server"}}).find("needs SWA_DISCOVERY_SERVER"), std::string::npos);
  EXPECT_NE(errorOf({{"SWA_TRANSPORT", "discovery-server"}, {"SWA_DISCOVERY_SERVER", "server:11811"}})
                .find("'server:11811' is not IPv4:PORT"),
            std::string::npos);
  // WHEN a server list is given without the discovery-server transport (the participant would silently ignore it)
  // THEN that is an error too
  EXPECT_NE(errorOf({{"SWA_DISCOVERY_SERVER", "127.0.0.1:11811"}}).find("SWA_TRANSPORT is local"), std::string::npos);
}

TEST(Deployment, SwarmNameIsAPartitionOfItsOwn) {
  // WHEN SWA_SWARM is unset THEN the default partition is used (issue #11: one swarm per run)
  EXPECT_TRUE(dds::parseDeployment(envOf({})).swarm.empty());
  // WHEN it names a swarm THEN its partition is "swa." and the name
  EXPECT_EQ(dds::parseDeployment(envOf({{"SWA_SWARM", "field-test_2.b"}})).swarm, "field-test_2.b");
  EXPECT_EQ(dds::swarmPartition("field-test_2.b"), "swa.field-test_2.b");
  // WHEN the name is no partition name, or would be a wildcard pattern, THEN it is refused
  for (const std::string& bad : std::vector<std::string>{"two words", "swa*", "a/b", std::string(65, 'x')}) {
    EXPECT_NE(errorOf({{"SWA_SWARM", bad}}).find("SWA_SWARM: '"), std::string::npos) << bad;
  }
  // WHEN it is combined with DDS Security (the permissions grant the default partition only) THEN it is refused,
  // saying why
  EXPECT_NE(errorOf({{"SWA_SWARM", "a"}, {"SWA_SECURITY_DIR", "/creds"}}).find("cannot be combined"),
            std::string::npos);
}

TEST(Deployment, ServerListIsCheckedEntryByEntry) {
  // WHEN a list of IPv4:PORT servers is checked THEN it has no problem
  EXPECT_TRUE(dds::checkServerList("127.0.0.1:11811").empty());
  EXPECT_TRUE(dds::checkServerList("10.0.0.1:1;192.168.255.254:65535").empty());
  // WHEN it is empty, lacks a port, has port 0 or 65536 or an address out of range THEN it has one problem
  EXPECT_EQ(dds::checkServerList("").size(), 1u);
  EXPECT_EQ(dds::checkServerList("127.0.0.1").size(), 1u);
  EXPECT_EQ(dds::checkServerList("127.0.0.1:0").size(), 1u);
  EXPECT_EQ(dds::checkServerList("127.0.0.1:65536").size(), 1u);
  EXPECT_EQ(dds::checkServerList("256.0.0.1:11811").size(), 1u);
  // AND each bad entry of a list is one problem
  EXPECT_EQ(dds::checkServerList("1.2.3:11811;1.2.3.4.5:11811;1.2.3.4:x").size(), 3u);
}

TEST(Deployment, SecurityFilesAreNamedAfterTheParticipant) {
  // WHEN the credential files of participant swa_agent_3 in /creds are named
  const dds::SecurityFiles f = dds::securityFiles("/creds", "swa_agent_3");
  // THEN the CA and governance are shared, the certificate, key and permissions are the participant's own
  EXPECT_EQ(f.ca, "/creds/ca.pem");
  EXPECT_EQ(f.governance, "/creds/governance.p7s");
  EXPECT_EQ(f.certificate, "/creds/swa_agent_3/cert.pem");
  EXPECT_EQ(f.private_key, "/creds/swa_agent_3/key.pem");
  EXPECT_EQ(f.permissions, "/creds/swa_agent_3/permissions.p7s");
  // AND SWA_SECURITY_DIR gives that directory
  EXPECT_EQ(dds::parseDeployment(envOf({{"SWA_SECURITY_DIR", "/creds"}})).security_dir, "/creds");
}

TEST(Deployment, UnreadableCredentialsAreListed) {
  // GIVEN a credentials directory with swa_sim's files but its permissions
  namespace fs = std::filesystem;
  const swa::testing::ScratchDir scratch("swa_test_creds");
  const fs::path& dir = scratch.path();
  fs::create_directories(dir / "swa_sim");
  for (const char* f : {"ca.pem", "governance.p7s", "swa_sim/cert.pem", "swa_sim/key.pem"})
    std::ofstream(dir / f) << "x";
  // WHEN the unreadable files of swa_sim are listed THEN only its permissions are
  const auto missing = dds::unreadableFiles(dds::securityFiles(dir.string(), "swa_sim"));
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0], (dir / "swa_sim" / "permissions.p7s").string());
  // AND swa_agent_0, with no directory of its own, lacks its certificate, key and permissions
  EXPECT_EQ(dds::unreadableFiles(dds::securityFiles(dir.string(), "swa_agent_0")).size(), 3u);
}

TEST(LaunchDeploymentOptions, PastThirtyTwoUavProcessesDiscoveryGoesThroughAServerUnlessATransportIsAskedFor) {
  const launch::LaunchOptions plain = launch::parseLaunchOptions({"--scenario", "s"});
  // GIVEN nothing asked for THEN 32 UAV processes keep the default, 33 get a discovery server
  EXPECT_EQ(launch::automaticTransport(plain, nullptr, 32), std::nullopt);
  EXPECT_EQ(launch::automaticTransport(plain, nullptr, 33), "discovery-server");
  EXPECT_EQ(launch::automaticTransport(plain, "", 128), "discovery-server");  // SWA_TRANSPORT= (empty) asks nothing
  // GIVEN a transport asked for, on the command line or in the environment THEN it stays, however many
  EXPECT_EQ(
      launch::automaticTransport(launch::parseLaunchOptions({"--scenario", "s", "--transport", "local"}), nullptr, 128),
      std::nullopt);
  EXPECT_EQ(launch::automaticTransport(plain, "network", 128), std::nullopt);
  // GIVEN DDS Security (a server would need credentials of its own) or named servers THEN nothing is chosen
  EXPECT_EQ(
      launch::automaticTransport(launch::parseLaunchOptions({"--scenario", "s", "--secure", "creds"}), nullptr, 128),
      std::nullopt);
  launch::LaunchOptions servers = plain;
  servers.discovery_server = "127.0.0.1:11900";
  EXPECT_EQ(launch::automaticTransport(servers, nullptr, 128), std::nullopt);
}

TEST(LaunchDeploymentOptions, ParsedAndChecked) {
  // WHEN the launcher is given a discovery-server transport with a server, and credentials
  const launch::LaunchOptions o =
      launch::parseLaunchOptions({"--scenario", "s.yaml", "--transport", "discovery-server", "--discovery-server",
                                  "127.0.0.1:11900", "--secure", "creds"});
  // THEN it keeps them
  EXPECT_EQ(o.transport, "discovery-server");
  EXPECT_EQ(o.discovery_server, "127.0.0.1:11900");
  EXPECT_EQ(o.secure_dir, "creds");
  // AND it reads the discovery port and the swarm (in both spellings), and refuses a swarm name with a space
  EXPECT_EQ(launch::parseLaunchOptions({"--scenario", "s", "--discovery-port", "12000"}).discovery_port, 12000);
  EXPECT_EQ(launch::parseLaunchOptions({"--scenario", "s", "--swarm", "none"}).swarm, "none");
  EXPECT_EQ(launch::parseLaunchOptions({"--scenario", "s", "--swarm=lab-3"}).swarm, "lab-3");
  EXPECT_THROW(launch::parseLaunchOptions({"--scenario", "s", "--swarm", "lab 3"}), std::invalid_argument);
  // WHEN every deployment option is wrong at once THEN they are refused, every problem named
  try {
    launch::parseLaunchOptions({"--scenario", "s", "--transport", "tcp", "--discovery-server", "host:1",
                                "--discovery-port", "80", "--secure", ""});
    FAIL() << "accepted bad deployment options";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--transport must be local, network or discovery-server, got 'tcp'"), std::string::npos);
    EXPECT_NE(what.find("--discovery-server: 'host:1' is not IPv4:PORT"), std::string::npos);
    EXPECT_NE(what.find("--discovery-port '80'"), std::string::npos);
    EXPECT_NE(what.find("--secure needs the credentials directory"), std::string::npos);
    EXPECT_NE(what.find("--discovery-server needs --transport discovery-server"), std::string::npos);
  }
}

TEST(LaunchDeploymentOptions, ASecureLaunchStaggersItsUavProcessesUnlessToldOtherwise) {
  // A plain launch starts everything at once; a secure one one UAV process every kSecureStaggerS (its handshakes
  // stall when many start together); --stagger-s says otherwise either way.
  EXPECT_EQ(launch::staggerOf(launch::parseLaunchOptions({"--scenario", "s"})), 0.0);
  EXPECT_EQ(launch::staggerOf(launch::parseLaunchOptions({"--scenario", "s", "--secure", "creds"})),
            launch::kSecureStaggerS);
  EXPECT_EQ(launch::staggerOf(launch::parseLaunchOptions({"--scenario", "s", "--secure", "creds", "--stagger-s", "0"})),
            0.0);
  EXPECT_EQ(launch::staggerOf(launch::parseLaunchOptions({"--scenario", "s", "--stagger-s", "0.25"})), 0.25);
  for (const char* bad : {"-1", "11", "nan", "0.5s", ""}) {
    try {
      launch::parseLaunchOptions({"--scenario", "s", "--stagger-s", bad});
      FAIL() << "accepted --stagger-s '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      const std::string expected = "--stagger-s '" + std::string(bad) + "' is not a delay in seconds in [0, 10]";
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace swa
