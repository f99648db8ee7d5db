#pragma once
// The messages between rlrun and a Python env worker (worker.py, which must agree with this
// file). One Unix stream socket per worker; little-endian, packed.
//
// Handshake: rlrun sends u32 length + JSON {"target": "python:mod:Class" | "gymnasium:ID" |
// "pettingzoo:mod:function", "kwargs": {...}, "turn_based": {"opponent", "learner_side"},
// "agent_indicator": "none" | "agent" | "type"};
// the worker answers u32 length + JSON: {"ok": true, "protocol": 1, "observation_space": S,
// "action_space": S, "obs_dim", "act_dim", "render_mode", "render_fps", "max_episode_steps",
// "num_agents", "agents", "class", "python", "python_version", ...} or
// {"ok": false, "error": "<message or traceback>"}. A space S is {"kind": "Box", "shape",
// "low", "high", "dtype"} (bounds as numbers or "inf" / "-inf"), {"kind": "Discrete", "n",
// "start"}, {"kind": "MultiDiscrete", "nvec"}, {"kind": "MultiBinary", "n"} or
// {"kind": "Dict", "spaces": {key: S}}.
//
// A Gymnasium env has num_agents 1; a PettingZoo env (pettingzoo_agents.py) k agents named
// by "agents", each with the spaces described (agent-major rows below).
//
// Then fixed-size requests of kRequestOp + max(9, 4 * act_dim * k) bytes:
//   'R' u8 has_seed, u64 seed        reset(seed=seed) or reset()
//   'S' f32[k * act_dim]             step(action), every agent's action
//   'F'                              render()
//   'C'                              close(), then the worker exits
// and replies 'K' or 'E', u32 body length, body:
//   reset/step 'K': f64 reward[k], u8 terminated[k], u8 truncated[k], f32[k * obs_dim]
//                   observations,
//                   u16 n_new_keys, n_new_keys x (u16 length, UTF-8 name),
//                   u16 n_values, n_values x (u16 key index, f64 value)
//                   (numeric info; a key's index is its order of first appearance)
//   render 'K':     u32 height, u32 width, height * width * 3 bytes RGB (0 x 0: no frame)
//   'E':            UTF-8 text: the env's traceback or the problem with what it returned
#include <cstddef>
#include <cstdint>

namespace rlrun::python_protocol {

inline constexpr int kVersion = 1;
inline constexpr char kReset = 'R';
inline constexpr char kStep = 'S';
inline constexpr char kRender = 'F';
inline constexpr char kClose = 'C';
inline constexpr char kOk = 'K';
inline constexpr char kError = 'E';

// Bytes of one request for an action of act_dim floats.
inline size_t request_bytes(int act_dim) {
  const size_t action = 4 * static_cast<size_t>(act_dim);
  return 1 + (action > 9 ? action : 9);
}

// Bounds on what a worker may send (it runs the user's own code, but a broken env must not
// make rlrun allocate without limit): handshake JSON (a Box of an 84x84x3 image with bounds
// is ~0.5 MB), an error text, a frame (4096 x 4096 RGB), info keys per env (256 of the env's
// own and up to 4096 entries of an action mask, env/action_mask.hpp).
inline constexpr uint32_t kMaxHandshakeBytes = 64u << 20;
inline constexpr uint32_t kMaxErrorBytes = 1u << 20;
inline constexpr uint32_t kMaxReplyBytes = 64u << 20;
inline constexpr int kMaxInfoKeys = 256 + 4096;
// Agents of one env (a traffic city has hundreds of lights; more is a broken handshake).
inline constexpr int kMaxAgents = 65536;

}  // namespace rlrun::python_protocol
