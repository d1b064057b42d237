#include "swa/px4/release.h"

namespace swa::px4 {

const char* releaseName(Release r) {
  switch (r) {
    case Release::kV1_15:
      return "v1.15";
    case Release::kV1_16:
      return "v1.16";
    case Release::kV1_17:
      return "v1.17";
  }
  return "?";
}

std::optional<Release> parseRelease(std::string_view text) {
  if (!text.empty() && text.front() == 'v') text.remove_prefix(1);
  for (const Release r : kReleases) {
    const std::string_view name = std::string_view(releaseName(r)).substr(1);  // "1.17"
    if (text == name) return r;
    // A patch release: "1.17." followed by digits only.
    if (text.size() > name.size() + 1 && text.substr(0, name.size()) == name && text[name.size()] == '.' &&
        text.substr(name.size() + 1).find_first_not_of("0123456789") == std::string_view::npos) {
      return r;
    }
  }
  return std::nullopt;
}

std::string releaseList() {
  std::string s;
  for (const Release r : kReleases) s += std::string(s.empty() ? "" : ", ") + releaseName(r);
  return s;
}

int messageVersion(Release r, std::string_view message) {
  // From the releases' msg/versioned/*.msg (MESSAGE_VERSION): v1.16 versions VehicleStatus, v1.17 also
  // VehicleLocalPosition; every other message SWA uses is at version 0.
  if (message == "vehicle_status") return r == Release::kV1_15 ? 0 : 1;
  if (message == "vehicle_local_position") return r == Release::kV1_17 ? 1 : 0;
  return 0;
}

std::string topicName(Release r, std::string_view message) {
  const int version = messageVersion(r, message);
  std::string name(message);
  if (version > 0) name += "_v" + std::to_string(version);
  return name;
}

}  // namespace swa::px4
