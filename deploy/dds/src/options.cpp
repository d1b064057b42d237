#include "swa/dds/options.h"

#include <cstdlib>
#include <stdexcept>

#include "swa/app/number.h"

#ifndef SWA_DEFAULT_PROFILES_FILE
#error "SWA_DEFAULT_PROFILES_FILE must be defined by the build"
#endif

namespace swa::dds {

int resolveDomain(const std::optional<std::string>& cli_value) {
  std::string source = "--domain";
  std::string text;
  if (cli_value) {
    text = *cli_value;
  } else if (const char* env = std::getenv("SWA_DOMAIN"); env != nullptr && *env != '\0') {
    source = "SWA_DOMAIN";
    text = env;
  } else {
    return 0;
  }
  const auto value = app::parseInteger(text, 0, kMaxDomainId);
  if (!value) {
    throw std::invalid_argument(source + " = '" + text + "' is not a DDS domain id (an integer in [0, " +
                                std::to_string(kMaxDomainId) + "])");
  }
  return static_cast<int>(*value);
}

std::string resolveProfilesFile() {
  if (const char* env = std::getenv("SWA_DDS_PROFILES"); env != nullptr && *env != '\0') return env;
  return SWA_DEFAULT_PROFILES_FILE;
}

}  // namespace swa::dds
