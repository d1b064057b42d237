#pragma once
// Wind gust acceleration as a 2-D Ornstein-Uhlenbeck process, discretised exactly (not Euler): with
// phi = exp(-dt / corr), x_{k+1} = phi x_k + std sqrt(1 - phi^2) n_k keeps the stationary std and the
// autocorrelation exp(-|lag| / corr) for any step size.

#include "swa/agent/geometry.h"
#include "swa/sim/random.h"

namespace swa::sim {

class OuProcess2 {
 public:
  // Starts from a stationary draw: wind does not begin at rest when the scenario starts. corr_s <= 0 gives white
  // noise, std <= 0 a process that stays at zero (and draws nothing).
  OuProcess2(double std, double corr_s, double dt_s, Rng rng);

  void advance();
  const agent::Vec2& value() const { return value_; }

 private:
  agent::Vec2 draw();

  double phi_ = 0.0;
  double innovation_std_ = 0.0;
  bool active_ = false;
  Rng rng_;
  agent::Vec2 value_ = agent::Vec2::Zero();
};

}  // namespace swa::sim
