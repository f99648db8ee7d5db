#!/usr/bin/env bash
# Regenerates configs/zoo/ with `rlrun zoo import` from a checkout of rl-baselines3-zoo:
# the entries of its algorithm files (SB3's six and sb3-contrib's TQC, QR-DQN, TRPO, ARS,
# CrossQ and RecurrentPPO's ppo_lstm) for the classic-control (with the zoo's *NoVel variants),
# Box2D and MuJoCo tasks (docs/zoo.md). MuJoCo entries the zoo keeps under v2 only (PPO's
# InvertedPendulum-v2, Reacher-v2, ...) are imported for the v4 task (docs/mujoco.md).
#   scripts/data/regen_zoo_configs.sh ZOO_CHECKOUT [RLRUN_BINARY]
# An entry the file does not have (e.g. DQN on Pendulum) is skipped; an entry that needs what
# this rlrun build lacks is reported and skipped, and the script exits 1 at the end.
set -euo pipefail
zoo=${1:?usage: scripts/data/regen_zoo_configs.sh ZOO_CHECKOUT [RLRUN_BINARY]}
here=$(cd "$(dirname "$0")/../.." && pwd)
rlrun=${2:-$here/build/rlrun}
out=$here/configs/zoo
mkdir -p "$out"
failed=0
cd "$zoo"  # the written files name hyperparams/<algo>.yml, not this machine's path
for algo in ppo a2c dqn qrdqn trpo ars sac td3 ddpg tqc crossq ppo_lstm; do
  file=hyperparams/$algo.yml
  for env in CartPole-v1 Pendulum-v1 MountainCar-v0 MountainCarContinuous-v0 Acrobot-v1 \
             LunarLander-v3 LunarLanderContinuous-v3 BipedalWalker-v3 BipedalWalkerHardcore-v3 \
             CarRacing-v3 \
             HalfCheetah-v4 Hopper-v4 Walker2d-v4 Ant-v4 Humanoid-v4 Swimmer-v4 \
             HumanoidStandup-v4 InvertedPendulum-v4 InvertedDoublePendulum-v4 Reacher-v4 \
             Pusher-v4 CartPoleNoVel-v1 PendulumNoVel-v1 MountainCarNoVel-v0 \
             MountainCarContinuousNoVel-v0 LunarLanderNoVel-v3 LunarLanderContinuousNoVel-v3; do
    # Only the env's own entry (or its v2 name, for the MuJoCo and LunarLander tasks):
    # `default` entries are not tuned for it.
    grep -q -e "^$env:" -e "^${env%-v4}-v2:" -e "^${env%-v3}-v2:" "$file" || continue
    # The zoo's SAC and TQC CarRacing entries read a pretrained autoencoder of another project
    # (ae.wrapper.AutoencoderWrapper, logs/car_racing_rgb_160.pkl): rlrun refuses them by name.
    [ "$env" = CarRacing-v3 ] && [ "$algo" != ppo ] && [ "$algo" != ppo_lstm ] && continue
    name=$(echo "${env%-v*}" | tr '[:upper:]' '[:lower:]')_$algo
    if "$rlrun" zoo import "$file" "$env" -o "$out/$name.yaml" 2>"$out/.$name.err"; then
      rm -f "$out/.$name.err"
    else
      echo "skipped $algo $env:" >&2
      cat "$out/.$name.err" >&2
      rm -f "$out/.$name.err"
      failed=1
    fi
  done
done
exit $failed
