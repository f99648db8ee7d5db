#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/numpy_pickle.hpp"
#include "rlrun/core/numpy_pickle_writer.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/utf8_text.hpp"
#include "rlrun/env/image_space.hpp"

namespace rlrun {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& why) {
  throw RuntimeFailure(what + ": " + why);
}

const PickleValue& required(const PickleValue& state, const char* name, const std::string& what) {
  const PickleValue* value = pickle_dict_get(state, name);
  if (!value) fail(what, std::string("a space without its '") + name + "' attribute");
  return *value;
}

std::vector<float> floats(const NumpyArray& array) {
  std::vector<float> out;
  for (const double v : array.to_doubles()) out.push_back(static_cast<float>(v));
  return out;
}

Space box(const PickleValue& state, const std::string& what) {
  const NumpyArray low = numpy_array(required(state, "low", what), what);
  const NumpyArray high = numpy_array(required(state, "high", what), what);
  const NumpyDtype dtype = numpy_dtype(required(state, "dtype", what), what);
  // float64 Boxes (Gymnasium's MuJoCo tasks) are float32 to rlrun, as to SB3's policy, which
  // casts observations to float32 (obs_as_tensor).
  BoxDtype box_dtype = BoxDtype::kFloat32;
  if (dtype.kind == 'u' && dtype.item_bytes == 1)
    box_dtype = BoxDtype::kUint8;
  else if (dtype.kind != 'f')
    fail(what, "a Box of " + dtype.name() + " (rlrun's Box holds floats or uint8)");
  if (low.shape != high.shape) fail(what, "a Box whose low and high differ in shape");
  std::vector<int> shape;
  for (const int64_t d : low.shape) {
    if (d <= 0 || d > (int64_t{1} << 30)) fail(what, "a Box dimension of " + std::to_string(d));
    shape.push_back(static_cast<int>(d));
  }
  if (shape.empty()) shape.push_back(1);  // a 0-d Box holds one number
  return Space::box(floats(low), floats(high), shape, box_dtype);
}

Space discrete(const PickleValue& state, const std::string& what) {
  const int64_t n = pickled_integer(required(state, "n", what), what);
  const PickleValue* start = pickle_dict_get(state, "start");
  return Space::discrete(n, start ? pickled_integer(*start, what) : 0);
}

Space multi_discrete(const PickleValue& state, const std::string& what) {
  const NumpyArray nvec = numpy_array(required(state, "nvec", what), what);
  if (nvec.shape.size() != 1) fail(what, "a MultiDiscrete of more than one dimension");
  if (const PickleValue* start = pickle_dict_get(state, "start"))
    for (const double s : numpy_array(*start, what).to_doubles())
      if (s != 0) fail(what, "a MultiDiscrete whose values do not start at 0");
  std::vector<int64_t> counts;
  for (const double v : nvec.to_doubles()) counts.push_back(static_cast<int64_t>(v));
  return Space::multi_discrete(counts);
}

Space multi_binary(const PickleValue& state, const std::string& what) {
  const PickleValue& n = required(state, "n", what);
  if (n.kind != PickleKind::kInt || n.integer <= 0 || n.integer > (int64_t{1} << 30))
    fail(what, "a MultiBinary whose n is not a positive int (rlrun reads one dimension)");
  return Space::multi_binary(static_cast<int>(n.integer));
}

Space space_of(const PickleValue& value, const std::string& what, bool inside_dict);

Space dict(const PickleValue& state, const std::string& what, bool nested) {
  if (nested) fail(what, "a Dict inside a Dict (SB3's MultiInputPolicy reads one level)");
  const std::vector<const PickleValue*>* items = pickle_dict_items(required(state, "spaces", what));
  if (!items || items->empty()) fail(what, "a Dict without spaces");
  std::vector<std::pair<std::string, Space>> entries;
  for (std::size_t i = 0; i + 1 < items->size(); i += 2) {
    const PickleValue& key = *(*items)[i];
    if (key.kind != PickleKind::kString || key.text.empty() || key.text.size() > 100)
      fail(what, "a Dict key that is not a short string");
    entries.emplace_back(
        key.text, space_of(*(*items)[i + 1], what + "['" + quoted_text(key.text) + "']", true));
  }
  return Space::dict(std::move(entries));
}

Space space_of(const PickleValue& value, const std::string& what, bool inside_dict) {
  const PickleValue* callee = value.callee();
  const bool space_class = callee && (callee->module.starts_with("gymnasium.spaces.") ||
                                      callee->module.starts_with("gym.spaces."));
  if (!space_class || !value.state)
    fail(what, describe_pickle_value(value) + ", not a Gymnasium space");
  const PickleValue& state = *value.state;
  try {
    if (callee->text == "Box") return box(state, what);
    if (callee->text == "Discrete") return discrete(state, what);
    if (callee->text == "MultiDiscrete") return multi_discrete(state, what);
    if (callee->text == "MultiBinary") return multi_binary(state, what);
    if (callee->text == "Dict") return dict(state, what, inside_dict);
  } catch (const std::invalid_argument& e) {  // Space's own checks
    fail(what, e.what());
  }
  fail(what, "a " + callee->text +
                 " space (rlrun reads Box, Discrete, MultiDiscrete, "
                 "MultiBinary and Dict)");
}

// Gymnasium's module (under gymnasium.spaces) and class for each kind of space.
struct GymnasiumClass {
  const char* file;
  const char* name;
};
GymnasiumClass gymnasium_class(SpaceKind kind) {
  switch (kind) {
    case SpaceKind::kBox: return {"box", "Box"};
    case SpaceKind::kDiscrete: return {"discrete", "Discrete"};
    case SpaceKind::kMultiDiscrete: return {"multi_discrete", "MultiDiscrete"};
    case SpaceKind::kMultiBinary: return {"multi_binary", "MultiBinary"};
    case SpaceKind::kDict: return {"dict", "Dict"};
  }
  throw RuntimeFailure("a space Gymnasium has no class for");
}

// Writing: NEWOBJ(cls, ()) then BUILD with the attributes of `state` written by the caller
// between begin_space_state() and end_space_state().
void begin_space_state(PickleWriter& p, SpaceKind kind) {
  const GymnasiumClass c = gymnasium_class(kind);
  p.global_ref(std::string("gymnasium.spaces.") + c.file, c.name);
  p.empty_tuple();
  p.new_object();
  p.empty_dict();
  p.mark();
}
void end_space_state(PickleWriter& p) {
  p.text("_np_random");
  p.none();
  p.set_items();
  p.build();
}

std::vector<int64_t> dims(const std::vector<int>& shape) {
  return std::vector<int64_t>(shape.begin(), shape.end());
}

void pickle_box(PickleWriter& p, const Space& space) {
  const bool uint8 = space.is_uint8_box();
  const std::vector<int64_t> shape = dims(space.shape());
  const auto bounds = [&](const std::vector<float>& values) {
    if (!uint8) return pickle_numpy_float32_array(p, values, shape);
    std::vector<uint8_t> bytes;
    for (const float v : values) bytes.push_back(static_cast<uint8_t>(v));
    pickle_numpy_array(p, "u1", shape, bytes);
  };
  std::vector<bool> below;
  std::vector<bool> above;
  for (const float v : space.low()) below.push_back(!std::isinf(v));
  for (const float v : space.high()) above.push_back(!std::isinf(v));
  begin_space_state(p, SpaceKind::kBox);
  p.text("dtype");
  pickle_numpy_dtype(p, uint8 ? "u1" : "f4");
  p.text("_shape");
  p.int_tuple(shape);
  p.text("low");
  bounds(space.low());
  p.text("high");
  bounds(space.high());
  p.text("bounded_below");
  pickle_numpy_bool_array(p, below, shape);
  p.text("bounded_above");
  pickle_numpy_bool_array(p, above, shape);
  end_space_state(p);
}

void pickle_space(PickleWriter& p, const Space& space) {
  switch (space.kind()) {
    case SpaceKind::kBox: return pickle_box(p, space);
    case SpaceKind::kDiscrete:
      begin_space_state(p, SpaceKind::kDiscrete);
      p.text("n");
      pickle_numpy_int64(p, space.n());
      p.text("start");
      pickle_numpy_int64(p, space.start());
      p.text("_shape");
      p.empty_tuple();
      p.text("dtype");
      pickle_numpy_dtype(p, "i8");
      return end_space_state(p);
    case SpaceKind::kMultiDiscrete:
      begin_space_state(p, SpaceKind::kMultiDiscrete);
      p.text("nvec");
      pickle_numpy_int64_array(p, space.nvec());
      p.text("start");
      pickle_numpy_int64_array(p, std::vector<int64_t>(space.nvec().size(), 0));
      p.text("_shape");
      p.int_tuple({static_cast<int64_t>(space.nvec().size())});
      p.text("dtype");
      pickle_numpy_dtype(p, "i8");
      return end_space_state(p);
    case SpaceKind::kMultiBinary:
      begin_space_state(p, SpaceKind::kMultiBinary);
      p.text("n");
      p.integer(space.n());
      p.text("_shape");
      p.int_tuple({space.n()});
      p.text("dtype");
      pickle_numpy_dtype(p, "i1");
      return end_space_state(p);
    case SpaceKind::kDict:
      begin_space_state(p, SpaceKind::kDict);
      p.text("spaces");
      p.empty_dict();
      p.mark();
      for (std::size_t i = 0; i < space.keys().size(); ++i) {
        // Python decodes the key as UTF-8; a key that is not printable UTF-8 is refused
        // rather than written as a pickle that would not load.
        if (printable_utf8(space.keys()[i]) != space.keys()[i])
          throw RuntimeFailure("the Dict key '" + quoted_text(space.keys()[i]) +
                               "' is not printable UTF-8 (a Python str)");
        p.text(space.keys()[i]);
        pickle_space(p, space.subspaces()[i]);
      }
      p.set_items();
      p.text("_shape");
      p.none();
      p.text("dtype");
      p.none();
      return end_space_state(p);
  }
  throw RuntimeFailure("a space Gymnasium has no class for: " + space.describe());
}

}  // namespace

void pickle_gymnasium_space(PickleWriter& p, const Space& space) { pickle_space(p, space); }

std::string gymnasium_space_class(const Space& space) {
  const GymnasiumClass c = gymnasium_class(space.kind());
  return std::string("gymnasium.spaces.") + c.file + "." + c.name;
}

bool is_sb3_space_global(const std::string& module, const std::string& name) {
  // Gymnasium's, and gym's before it (SB3 1.x files: gym 0.21's spaces, the same attributes).
  for (const char* package : {"gymnasium.spaces.", "gym.spaces."}) {
    if (!module.starts_with(package)) continue;
    const std::string file = module.substr(std::string(package).size());
    return (file == "box" && name == "Box") || (file == "discrete" && name == "Discrete") ||
           (file == "multi_discrete" && name == "MultiDiscrete") ||
           (file == "multi_binary" && name == "MultiBinary") || (file == "dict" && name == "Dict");
  }
  if (module == "collections") return name == "OrderedDict";
  // A seeded space's generator: kept in the tree, never read.
  if (module == "numpy.random._pickle")
    return name == "__generator_ctor" || name == "__bit_generator_ctor" ||
           name == "__randomstate_ctor";
  return is_numpy_pickle_global(module, name);
}

Space sb3_space(const PickleValue& value, const std::string& what) {
  return space_of(value, what, false);
}

namespace sb3_spaces_detail {

// `space` (a 3-d Box) with its axes in the order `axes` (numpy's transpose).
Space transposed_box(const Space& space, const std::array<int, 3>& axes) {
  const std::vector<int>& in = space.shape();
  if (!space.is_box() || in.size() != 3)
    throw std::invalid_argument("an image space is a 3-dimensional Box");
  const std::vector<int> out = {in[axes[0]], in[axes[1]], in[axes[2]]};
  std::vector<float> low(space.low().size()), high(space.high().size());
  std::array<int, 3> at{};  // the output element's index along each output axis
  for (at[0] = 0; at[0] < out[0]; ++at[0])
    for (at[1] = 0; at[1] < out[1]; ++at[1])
      for (at[2] = 0; at[2] < out[2]; ++at[2]) {
        std::array<int, 3> source{};
        for (int k = 0; k < 3; ++k) source[axes[k]] = at[k];
        const size_t from =
            (static_cast<size_t>(source[0]) * in[1] + source[1]) * in[2] + source[2];
        const size_t to = (static_cast<size_t>(at[0]) * out[1] + at[1]) * out[2] + at[2];
        low[to] = space.low()[from];
        high[to] = space.high()[from];
      }
  return Space::box(std::move(low), std::move(high), out, space.dtype());
}

}  // namespace sb3_spaces_detail

Space channels_first_image(const Space& hwc) {
  return sb3_spaces_detail::transposed_box(hwc, {2, 0, 1});
}

Space channels_last_image(const Space& chw) {
  return sb3_spaces_detail::transposed_box(chw, {1, 2, 0});
}

namespace sb3_spaces_detail {
// Each key of a Dict that SB3's is_image_space calls an image (env/image_space.hpp) and whose
// layout is not `channels_last` yet, transposed by `transpose`; other keys as they are.
Space dict_images_as(const Space& space, bool channels_last,
                     Space (*transpose)(const Space& image)) {
  if (!space.is_dict()) return space;
  std::vector<std::pair<std::string, Space>> entries;
  for (size_t i = 0; i < space.keys().size(); ++i) {
    const Space& sub = space.subspaces()[i];
    const std::optional<ImageInput> image = image_input(sub, /*normalize_images=*/true);
    entries.emplace_back(space.keys()[i],
                         image && image->channels_last != channels_last ? transpose(sub) : sub);
  }
  return Space::dict(std::move(entries));
}
}  // namespace sb3_spaces_detail

Space channels_first_dict_images(const Space& space) {
  return sb3_spaces_detail::dict_images_as(space, /*channels_last=*/false, channels_first_image);
}

Space channels_last_dict_images(const Space& space) {
  return sb3_spaces_detail::dict_images_as(space, /*channels_last=*/true, channels_last_image);
}

}  // namespace rlrun
