#pragma once
// numpy values written into a pickle (core/pickle_writer.hpp) without numpy, in the forms
// numpy 1.x writes for protocols 2-4 and every numpy since 1.0 (and numpy 2, through its
// numpy.core compatibility names) reads; core/numpy_pickle.hpp reads the same forms:
//  * a dtype: numpy.dtype('f4', False, True) then BUILD (3, byte order, None, None, None, -1,
//    -1, 0) (numpy/core/src/multiarray/descriptor.c: arraydescr_reduce, arraydescr_setstate);
//  * an array: numpy.core.multiarray._reconstruct(numpy.ndarray, (0,), b'b') then BUILD
//    (1, shape, dtype, False, raw bytes) (methods.c: array_reduce, array_setstate);
//  * a scalar: numpy.core.multiarray.scalar(dtype, raw bytes).
// The pickle must be protocol 3 or higher (raw bytes are BINBYTES).
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/pickle_writer.hpp"

namespace rlrun {

// A numpy type code with its byte order: "f4", "f8", "i8", "i1", "u1" or "b1" (bool).
void pickle_numpy_dtype(PickleWriter& p, const std::string& code);
// An array of `code` with `shape`, `bytes` its elements in C order, little-endian.
void pickle_numpy_array(PickleWriter& p, const std::string& code, const std::vector<int64_t>& shape,
                        const std::vector<uint8_t>& bytes);
void pickle_numpy_float32_array(PickleWriter& p, const std::vector<float>& values,
                                const std::vector<int64_t>& shape);
void pickle_numpy_int64_array(PickleWriter& p, const std::vector<int64_t>& values);
void pickle_numpy_bool_array(PickleWriter& p, const std::vector<bool>& values,
                             const std::vector<int64_t>& shape);
// np.int64(value).
void pickle_numpy_int64(PickleWriter& p, int64_t value);

}  // namespace rlrun
