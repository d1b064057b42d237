#pragma once
// The PX4 releases SWA speaks to, and what differs between them on the wire for the messages SWA uses
// (tests/px4/test_px4_definitions.cpp checks every layout against PX4's own .msg files of each release):
// - VehicleStatus lost two fields in v1.16 (avoidance_system_required, avoidance_system_valid): its bytes differ.
// - VehicleLocalPosition changed its distance-to-ground fields in v1.16; SensorGps gained two fields in v1.17.
// - From v1.16 PX4's uXRCE-DDS client names the topic of a message whose definition has MESSAGE_VERSION = N > 0
//   <name>_v<N> (vehicle_status_v1); version 0 keeps the bare name. A subscriber on the wrong name matches nothing
//   and is told nothing, which is why the release is an explicit choice and not a guess.
// The type names on the wire (px4_msgs::msg::dds_::<T>_) are the same in every release.

#include <optional>
#include <string>
#include <string_view>

namespace swa::px4 {

enum class Release { kV1_15, kV1_16, kV1_17 };

constexpr Release kNewestRelease = Release::kV1_17;
constexpr Release kReleases[] = {Release::kV1_15, Release::kV1_16, Release::kV1_17};

// "v1.17" etc.
const char* releaseName(Release r);
// "1.17", "v1.17" or a patch release such as "v1.17.0"; nullopt for anything else (an unsupported release).
std::optional<Release> parseRelease(std::string_view text);
// "v1.15, v1.16, v1.17": for --help and error messages.
std::string releaseList();

// The uORB message's MESSAGE_VERSION in `r` for the messages SWA uses (0 where the release has no versioning).
// `message` is the topic's base name (vehicle_status, vehicle_local_position, ...).
int messageVersion(Release r, std::string_view message);
// The topic name PX4's uXRCE-DDS client of `r` uses for `message`: vehicle_status_v1 from v1.16, vehicle_status before.
std::string topicName(Release r, std::string_view message);

// Which layout a release has (idl/px4/<Message>_v<first release>.idl).
constexpr bool hasV116VehicleStatus(Release r) { return r != Release::kV1_15; }         // else v1.15's
constexpr bool hasV116VehicleLocalPosition(Release r) { return r != Release::kV1_15; }  // else v1.15's
constexpr bool hasV117SensorGps(Release r) { return r == Release::kV1_17; }             // else v1.15's

}  // namespace swa::px4
