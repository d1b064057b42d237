#include "swa/agent/config.h"

namespace swa::agent {

std::string toString(Mode mode) {
  switch (mode) {
    case Mode::kSwa:
      return "swa";
    case Mode::kStandalone:
      return "standalone";
    case Mode::kAnchored:
      return "anchored";
  }
  return "unknown";
}

std::string toString(CircleFit fit) {
  switch (fit) {
    case CircleFit::kFixedRadius:
      return "fixed_radius";
    case CircleFit::kAlgebraic:
      return "algebraic";
  }
  return "unknown";
}

std::string toString(NeighbourhoodRule rule) {
  switch (rule) {
    case NeighbourhoodRule::kGabriel:
      return "gabriel";
    case NeighbourhoodRule::kKNearest:
      return "k_nearest";
  }
  return "unknown";
}

}  // namespace swa::agent
