#pragma once
// The domain id and the profiles file of a DDS node, from its command line or the environment (no DDS include:
// testable on its own). The command lines themselves are read by swa/app/cli.h.

#include <optional>
#include <string>

namespace swa::dds {

// Highest usable domain id: Fast DDS maps domain d to UDP ports 7400 + 250 d + ..., which must stay below 65536.
constexpr int kMaxDomainId = 232;

// The domain id: `cli_value` (--domain) if given, else the environment variable SWA_DOMAIN, else 0.
// Throws std::invalid_argument naming the source when the value is not an integer in [0, kMaxDomainId].
int resolveDomain(const std::optional<std::string>& cli_value);

// The XML profiles file: the environment variable SWA_DDS_PROFILES if set and non-empty; else, for an installed
// program (<prefix>/bin/swa_sim), the installed <prefix>/share/swa/profiles.xml when it exists; else the source tree's
// idl/runtime/dds/profiles.xml (path compiled in: a program run from its build tree). Existence is checked by the
// Participant. A program of your own that links swa::dds lives elsewhere: give it SWA_DDS_PROFILES, or the path
// find_package(swa) sets in SWA_PROFILES_FILE.
std::string resolveProfilesFile();

}  // namespace swa::dds
