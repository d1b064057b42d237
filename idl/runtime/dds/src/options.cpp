#include "swa/dds/options.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "swa/app/number.h"

#ifndef SWA_DEFAULT_PROFILES_FILE
#error "SWA_DEFAULT_PROFILES_FILE must be defined by the build"
#endif
#ifndef SWA_INSTALLED_PROFILES_FROM_BIN
#error "SWA_INSTALLED_PROFILES_FROM_BIN must be defined by the build"
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
  // Relative to the program, so that an installed tree works wherever it was unpacked (the package is relocatable).
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = self.parent_path() / SWA_INSTALLED_PROFILES_FROM_BIN;
    if (std::filesystem::is_regular_file(installed, ec)) return installed.lexically_normal().string();
  }
  return SWA_DEFAULT_PROFILES_FILE;
}

}  // namespace swa::dds
