#include "swa/px4/vehicle.h"

namespace swa::px4 {

const char* navStateName(std::uint8_t nav_state) {
  switch (nav_state) {
    case 0:
      return "MANUAL";
    case 1:
      return "ALTCTL";
    case kNavStatePosctl:
      return "POSCTL";
    case 3:
      return "AUTO_MISSION";
    case kNavStateAutoLoiter:
      return "AUTO_LOITER";
    case 5:
      return "AUTO_RTL";
    case 12:
      return "DESCEND";
    case 13:
      return "TERMINATION";
    case kNavStateOffboard:
      return "OFFBOARD";
    case 15:
      return "STAB";
    case 17:
      return "AUTO_TAKEOFF";
    case 18:
      return "AUTO_LAND";
    default:
      return "other";
  }
}

}  // namespace swa::px4
