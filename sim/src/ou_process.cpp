#include "swa/sim/ou_process.h"

#include <cmath>

namespace swa::sim {

OuProcess2::OuProcess2(double std, double corr_s, double dt_s, Rng rng) : rng_(rng) {
  active_ = std > 0.0;
  if (!active_) return;
  phi_ = corr_s > 0.0 ? std::exp(-dt_s / corr_s) : 0.0;
  innovation_std_ = std * std::sqrt(1.0 - phi_ * phi_);
  value_ = std * draw();
}

agent::Vec2 OuProcess2::draw() {
  const double x = rng_.normal();
  const double y = rng_.normal();
  return {x, y};
}

void OuProcess2::advance() {
  if (active_) value_ = phi_ * value_ + innovation_std_ * draw();
}

}  // namespace swa::sim
