#!/usr/bin/env bash
# The board-game bars of issue 45 (docs/board_games.md): trains the tic-tac-toe and connect four
# configs for each seed, then plays each model against its benchmark opponents from both sides
# and prints win/draw/loss rates, the bar each must meet, and the training speed.
#   scripts/bench/board_games.sh [CONFIG...]       (default: the three board-game configs)
#   SEEDS="1 2 3" EPISODES=1000 scripts/bench/board_games.sh
# Bars: TicTacToe never loses to random and draws >= 95% against perfect play (minimax:9);
# ConnectFour beats minimax depth 2 in >= 80% of games as first player and >= 60% as second.
set -euo pipefail
cd "$(dirname "$0")/../.."
seeds=${SEEDS:-"1 2 3"}
episodes=${EPISODES:-1000}
configs=("$@")
((${#configs[@]})) || configs=(configs/tictactoe_maskable_ppo.yaml configs/tictactoe_self_play.yaml
                               configs/connect_four_maskable_ppo.yaml)
out=${OUT:-$(mktemp -d)}

# "win draw loss" rates of one evaluation (rlrun eval prints "  win = 0.950 (mean ...)").
rates() {
  local text=$1
  for key in win draw loss; do
    grep -E "^  $key = " <<<"$text" | awk '{printf "%s ", $3}'
  done
}

printf "%-28s %4s %10s %9s %-12s %-7s %s\n" config seed steps/s train_s opponent side "win draw loss"
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  case "$name" in
    tictactoe*) opponents="random minimax:9" ;;
    connect_four*) opponents="minimax:2 random" ;;
    *) opponents="random" ;;
  esac
  for seed in $seeds; do
    log=$(build/rlrun train "$config" --seed "$seed" --set run.out_dir="$out" \
          --set run.console_interval=1e9)
    summary=$(grep -E "^trained [0-9]+ steps in" <<<"$log" | tail -1)
    steps=$(awk '{print $2}' <<<"$summary")
    seconds=$(sed -E 's/.* in ([0-9.]+) s.*/\1/' <<<"$summary")
    speed=$(awk -v n="$steps" -v s="$seconds" 'BEGIN { printf "%.0f", n / s }')
    model="$out/$name/seed$seed/model.zip"
    for opponent in $opponents; do
      for side in first second; do
        text=$(build/rlrun eval --model "$model" --episodes "$episodes" --seed "$seed" \
               --opponent "$opponent" --side "$side")
        printf "%-28s %4s %10s %9s %-12s %-7s %s\n" "$name" "$seed" "$speed" "$seconds" \
          "$opponent" "$side" "$(rates "$text")"
      done
    done
  done
done
