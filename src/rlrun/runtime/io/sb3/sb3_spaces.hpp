#pragma once
// Gymnasium spaces as SB3 stores them in a model file's `data` (the cloudpickled
// `observation_space` and `action_space` entries), read into rlrun's Space without running the
// pickle (core/pickle_reader.hpp). A space pickles by reference to its class, then its
// __dict__ (gymnasium/spaces/box.py, discrete.py, multi_discrete.py, multi_binary.py, dict.py;
// SB3 1.x files hold gym 0.21's spaces, gym.spaces.*, with the attributes read here):
//   NEWOBJ(gymnasium.spaces.box.Box, ()) BUILD({'dtype': ..., '_shape': ..., 'low': array,
//   'high': array, ..., '_np_random': None or a numpy Generator})
// The random generator (numpy.random._pickle's constructors) is not read: rlrun's spaces are
// seeded by rlrun.
#include <string>

#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/pickle_writer.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// The globals a pickled space may name (gymnasium's space classes, numpy's array, dtype,
// scalar and random-generator constructors, collections.OrderedDict).
bool is_sb3_space_global(const std::string& module, const std::string& name);

// Box (float32 or uint8), Discrete, MultiDiscrete, MultiBinary, and a Dict of those. Throws
// RuntimeFailure naming `what` for any other value.
Space sb3_space(const PickleValue& value, const std::string& what);

// The other way (`rlrun export --format sb3`): `space` as Gymnasium 1.0 pickles it, in the form
// above, onto `p` (protocol 3 or higher), with `_np_random` None (Space.__setstate__ takes
// that, as a space never sampled). A float32 Box stays float32, a uint8 Box uint8; Discrete's
// n and start are np.int64, MultiDiscrete's nvec and start int64 arrays, MultiBinary int8.
void pickle_gymnasium_space(PickleWriter& p, const Space& space);
// The Gymnasium class that pickle names for `space`: "gymnasium.spaces.box.Box", ...
std::string gymnasium_space_class(const Space& space);

// SB3's VecTransposeImage (stable_baselines3/common/vec_env/vec_transpose.py): a CnnPolicy's
// file keeps the image space channels first, (C, H, W), where the env's is (H, W, C). Both
// take a 3-dimensional Box and keep its dtype and per-element bounds.
Space channels_first_image(const Space& hwc);
Space channels_last_image(const Space& chw);
// The same for the image keys of a Dict (SB3's VecTransposeImage transposes each key that
// is_image_space calls an image and that is not channels-first already: smallest axis first);
// other keys, and other spaces, as they are.
Space channels_first_dict_images(const Space& space);
Space channels_last_dict_images(const Space& space);

}  // namespace rlrun
