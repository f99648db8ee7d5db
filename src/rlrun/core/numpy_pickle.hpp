#pragma once
// numpy values inside a pickle (core/pickle_reader.hpp), read without numpy: how numpy 1.x and
// 2.x pickle them (numpy/core/src/multiarray/methods.c: array_reduce_ex, array_reduce;
// numpy/core/numeric.py: _frombuffer; numpy/core/src/multiarray/descriptor.c: arraydescr_reduce)
//  * an array, protocol 5: numpy.core.numeric._frombuffer(buffer, dtype, shape, order);
//  * an array, protocols 2-4: numpy.core.multiarray._reconstruct(numpy.ndarray, (0,), b'b')
//    then BUILD with (version, shape, dtype, is_fortran, raw bytes);
//  * a dtype: numpy.dtype('f4', False, True) then BUILD with (3, byte order, ...);
//  * a scalar (np.int64(2)): numpy.core.multiarray.scalar(dtype, raw bytes).
// numpy 2 names the modules numpy._core.*; both are accepted.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/pickle_reader.hpp"

namespace rlrun {

// The numpy globals those forms name (for a PickleGlobalFilter).
bool is_numpy_pickle_global(const std::string& module, const std::string& name);

// A dtype this reader decodes: little-endian (or single-byte) bool, int, uint or float.
struct NumpyDtype {
  char kind = 'f';  // 'b' bool, 'i' signed, 'u' unsigned, 'f' float
  int item_bytes = 4;
  std::string name() const;  // "float32", "int64", "bool", ...
};

struct NumpyArray {
  NumpyDtype dtype;
  std::vector<int64_t> shape;
  std::string bytes;  // C order, little-endian
  int64_t size() const;
  std::vector<double> to_doubles() const;  // every element as a double
};

// A dtype from its pickled call. Throws RuntimeFailure naming `what`.
NumpyDtype numpy_dtype(const PickleValue& value, const std::string& what);
// True when `value` is one of the array forms above.
bool is_numpy_array(const PickleValue& value);
// The array `value` pickles. Throws RuntimeFailure naming `what` for any other value, a dtype
// it does not decode, Fortran order in more than one dimension or bytes that do not match.
NumpyArray numpy_array(const PickleValue& value, const std::string& what);
// A Python int or a numpy integer scalar (np.int64(2)), as Gymnasium keeps Discrete's n.
int64_t pickled_integer(const PickleValue& value, const std::string& what);
// A Python float or int, a numpy scalar (np.float64(0.5)) or a one-element array, as a double
// (SB3's RunningMeanStd keeps a scalar's statistics in either form).
double pickled_number(const PickleValue& value, const std::string& what);

}  // namespace rlrun
