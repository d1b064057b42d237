#pragma once
// Whether a UDP port of this host is taken. Both the DDS participant ids (swa/dds/participant_id.h) and the discovery
// server swa_launch starts take the first free port of a range, beside other swarms and DDS users of the same host.

#include <optional>

namespace swa::app {

// True if binding 0.0.0.0:`port` without SO_REUSEADDR fails because it is in use (Fast DDS binds its unicast ports
// that way). Another process may still take a free port before the caller does: callers tolerate that race.
bool udpPortInUse(int port);

// The first port in [first, first + count) that is not in use, if any.
std::optional<int> firstFreeUdpPort(int first, int count);

}  // namespace swa::app
