#pragma once
// The version of this build, recorded in every report and study: the project's version and the commit it was built
// from, "-dirty" with uncommitted changes ("0.1.0+1a2b3c4d5e6f").

#include <string>

namespace swa::app {

std::string programVersion();

}  // namespace swa::app
