#pragma once
// What SAC.train (stable_baselines3/sac/sac.py) and TQC.train (sb3_contrib/tqc/tqc.py) share
// around their gradient step: the per-step scalars they log, and the loop over gradient_steps
// with the target update every target_update_interval steps of the call and the logged means.
// Each algorithm's gradient step itself stays in its own file.
#include <cstdint>

#include "rlrun/core/logger.hpp"

namespace rlrun {

// The per-step scalars SAC.train and TQC.train record (means over a train() call are logged).
struct EntropyRegularizedStepStats {
  double ent_coef = 0.0;       // alpha used in this step (before its update)
  double ent_coef_loss = 0.0;  // 0 when alpha is fixed
  double actor_loss = 0.0;
  double critic_loss = 0.0;    // SAC: 0.5 * sum over critics of mse; TQC: quantile Huber loss
};

// `gradient_steps` calls of step(update_target) — `if gradient_step % target_update_interval
// == 0`, counted within this call — then n_updates and the means on `logger` (if any), as
// SB3's train() records them.
template <class Step>
void train_entropy_regularized(int gradient_steps, int target_update_interval, float lr,
                               bool ent_coef_learned, int64_t& n_updates, Logger* logger,
                               Step&& step) {
  EntropyRegularizedStepStats sum;
  for (int k = 0; k < gradient_steps; ++k) {
    const EntropyRegularizedStepStats s = step(k % target_update_interval == 0);
    sum.ent_coef += s.ent_coef;
    sum.ent_coef_loss += s.ent_coef_loss;
    sum.actor_loss += s.actor_loss;
    sum.critic_loss += s.critic_loss;
  }
  n_updates += gradient_steps;
  if (!logger || gradient_steps == 0) return;
  const double n = gradient_steps;
  logger->record("train/n_updates", static_cast<double>(n_updates));
  logger->record("train/ent_coef", sum.ent_coef / n);
  logger->record("train/actor_loss", sum.actor_loss / n);
  logger->record("train/critic_loss", sum.critic_loss / n);
  if (ent_coef_learned) logger->record("train/ent_coef_loss", sum.ent_coef_loss / n);
  logger->record("train/learning_rate", lr);
}

}  // namespace rlrun
