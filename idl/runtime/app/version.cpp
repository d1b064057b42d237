#include "swa/app/version.h"

#include "swa_version.h"  // generated at build time (write_version.cmake)

namespace swa::app {

std::string programVersion() { return SWA_VERSION; }

}  // namespace swa::app
