"""C++'s std::mt19937 and the libstdc++ (GCC) distributions RLtools draws its evaluation start
states with (include/rl_tools/random/operations_cpu.h: a std::mt19937 seeded with seed + 1, a
fresh std::uniform_real_distribution<T> or std::normal_distribution<float> object per draw), so
that RLtools' own evaluation episodes can be replayed. Shared by rltools_cross_eval.py
(Pendulum) and rltools_cross_eval_ant.py (Ant-v4); checked against a C++ program compiled by
their tests.

The distributions follow libstdc++'s bits/random.h and random.tcc: generate_canonical<T, bits>
takes ceil(bits / 32) 32-bit draws, low word first, and divides their sum by 2^(32 k) (a result
of 1 becomes the largest value below 1); uniform_real_distribution is canonical * (b - a) + a;
normal_distribution is Marsaglia's polar method, whose second value a fresh object never uses.
Written with separate multiplies and adds: a caller built with -ffast-math -march=native (as
RLtools is) may fuse them, which moves the last bit of a draw."""
import ctypes
import ctypes.util
import math

import numpy as np


def mt19937_stream(seed):
    """The 32-bit outputs of C++'s std::mt19937(seed) (Matsumoto & Nishimura 1998)."""
    state = [0] * 624
    state[0] = seed & 0xFFFFFFFF
    for i in range(1, 624):
        state[i] = (1812433253 * (state[i - 1] ^ (state[i - 1] >> 30)) + i) & 0xFFFFFFFF
    index = 624
    while True:
        if index == 624:
            for i in range(624):
                y = (state[i] & 0x80000000) | (state[(i + 1) % 624] & 0x7FFFFFFF)
                state[i] = state[(i + 397) % 624] ^ (y >> 1) ^ (0x9908B0DF if y & 1 else 0)
            index = 0
        y = state[index]
        index += 1
        y ^= y >> 11
        y ^= (y << 7) & 0x9D2C5680
        y ^= (y << 15) & 0xEFC60000
        y ^= y >> 18
        yield y


def canonical_float(stream):
    """generate_canonical<float, 24>: one draw, float(u) / 2^32."""
    return float_of_draw(next(stream))


def float_of_draw(draw):
    """generate_canonical<float, 24> of one 32-bit draw (a result of 1 becomes the float below)."""
    x = np.float32(draw) / np.float32(4294967296.0)
    return np.nextafter(np.float32(1.0), np.float32(0.0)) if x >= np.float32(1.0) else x


def canonical_double(stream):
    """generate_canonical<double, 53>: two draws, (u0 + u1 2^32) / 2^64 in doubles."""
    total = float(next(stream))
    total += float(next(stream)) * 4294967296.0
    x = total / 18446744073709551616.0
    return math.nextafter(1.0, 0.0) if x >= 1.0 else x


def uniform_float(draw, low, high):
    """std::uniform_real_distribution<float>(low, high) from one 32-bit draw."""
    x = float_of_draw(draw)
    return np.float32(x * (np.float32(high) - np.float32(low))) + np.float32(low)


def uniform_double(stream, low, high):
    """std::uniform_real_distribution<double>(low, high): two 32-bit draws."""
    return canonical_double(stream) * (high - low) + low


def normal_float(stream, mean, std):
    """A fresh std::normal_distribution<float>(mean, std)'s first value (the polar method's
    y * sqrt(-2 log(r2) / r2), in floats)."""
    one, two = np.float32(1.0), np.float32(2.0)
    while True:
        x = two * canonical_float(stream) - one
        y = two * canonical_float(stream) - one
        r2 = x * x + y * y
        if r2 <= one and r2 != 0:
            break
    # std::log(float) is the C library's logf (glibc's is within one ulp of the true value, not
    # always the nearest float): called itself where it can be loaded.
    quotient = np.float32(np.float32(-2.0) * logf(r2)) / r2
    multiplier = np.float32(math.sqrt(float(quotient)))  # the double sqrt rounds to sqrtf's value
    return np.float32(np.float32(y * multiplier) * np.float32(std)) + np.float32(mean)


def _c_logf():
    try:
        libm = ctypes.CDLL(ctypes.util.find_library("m") or "libm.so.6")
        function = libm.logf
    except (OSError, AttributeError):
        return None
    function.argtypes, function.restype = [ctypes.c_float], ctypes.c_float
    return function


_LOGF = _c_logf()


def logf(x):
    """logf(x) as C computes it, or the float nearest log(x) without a C library."""
    if _LOGF is not None:
        return np.float32(_LOGF(float(x)))
    return np.float32(math.log(float(x)))
