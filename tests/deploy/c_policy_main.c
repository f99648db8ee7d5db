/* Runs an exported C policy (`rlrun export --format c`) on observations from a file:
 *   c_policy OBS.f32 ACTIONS.f32
 * OBS.f32: float32 observations, POLICY_OBS_DIM per step; ACTIONS.f32 gets POLICY_ACTION_DIM
 * float32 per step. A recurrent policy's (POLICY_STATE_DIM) steps are each preceded in OBS.f32 by
 * one float, 1 where an episode starts (the state is zeroed there). Built by tests/deploy/test_onnx_export.cpp with cc -std=c99 -Wall -Werror. */
#include <stdio.h>

#include "policy.h"

int main(int argc, char** argv) {
  float obs[POLICY_OBS_DIM], action[POLICY_ACTION_DIM];
  FILE *in, *out;
#ifdef POLICY_STATE_DIM
  float state[POLICY_STATE_DIM], start;
  int i;
  for (i = 0; i < POLICY_STATE_DIM; ++i) state[i] = 0.0f;
#endif
  if (argc != 3) return 2;
  in = fopen(argv[1], "rb");
  out = fopen(argv[2], "wb");
  if (!in || !out) return 1;
  for (;;) {
#ifdef POLICY_STATE_DIM
    if (fread(&start, sizeof(float), 1, in) != 1) break;
    if (start != 0.0f)
      for (i = 0; i < POLICY_STATE_DIM; ++i) state[i] = 0.0f;
#endif
    if (fread(obs, sizeof(float), POLICY_OBS_DIM, in) != POLICY_OBS_DIM) break;
#ifdef POLICY_STATE_DIM
    policy_act(obs, state, action);
#else
    policy_act(obs, action);
#endif
    if (fwrite(action, sizeof(float), POLICY_ACTION_DIM, out) != POLICY_ACTION_DIM) return 1;
  }
  return fclose(out) == 0 && fclose(in) == 0 ? 0 : 1;
}
