// swa_px4_bridge: PX4 (v1.15, v1.16, v1.17) <-> the swa_agent of one UAV. See --help (bridge_options.cpp).

#include <cstdio>
#include <memory>

#include "bridge_node.h"
#include "bridge_options.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"

namespace swa::bridge_node {
namespace {

app::Plan prepare(const std::vector<std::string>& args) {
  const BridgeOptions options = parseBridgeOptions(args);
  if (auto done = app::printIf(options.help, bridgeUsage)) return *done;
  const int domain = dds::resolveDomain(options.domain);
  return app::startWith([options, domain]() -> std::unique_ptr<app::Role> {
    return std::make_unique<BridgeNode>(options, domain, dds::resolveProfilesFile());
  });
}

}  // namespace
}  // namespace swa::bridge_node

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_px4_bridge", "command line", argc, argv, swa::bridge_node::prepare);
}
