"""Values crossing into C, checked in one place.

ctypes converts a Python int to a C integer by masking (2**32 + 3 becomes 3 in an int32_t) and numpy's
astype wraps the same way; a char* stops at the first NUL. Every integer argument of a library call
(_api wraps each function), every integer field of an options struct (options._assign) and every
integer array handed to the library (_arrays) goes through the functions below, which refuse what the
C type cannot hold instead of passing a different value on.
"""
import ctypes
import operator

import numpy as np

# The integer types of wefm.h's parameters and struct fields (c_int is c_int32 on our ABIs).
C_INTEGERS = (ctypes.c_int, ctypes.c_int32, ctypes.c_int64, ctypes.c_size_t)


def c_range(ctype):
    """(lowest, highest) value of a ctypes integer type."""
    bits = 8 * ctypes.sizeof(ctype)
    if ctype(-1).value == -1:
        return -(1 << (bits - 1)), (1 << (bits - 1)) - 1
    return 0, (1 << bits) - 1


def _type_name(lo, hi):
    bits = (hi - lo).bit_length()
    return "%sint%d" % ("" if lo < 0 else "u", bits)


def _integer(value, name):
    """value as a Python int; bools and numpy integers are integers, floats and strings are not."""
    try:
        return operator.index(value)
    except TypeError:
        raise TypeError("%s must be an integer, got %s %r" % (name, type(value).__name__, value)) from None


def _check_range(value, lo, hi, name):
    if value < lo or value > hi:
        raise OverflowError("%s = %d is out of range for %s (%d .. %d)"
                            % (name, value, _type_name(lo, hi), lo, hi))


def c_integer(value, ctype, name):
    """value as an int that `ctype` holds exactly: TypeError if not an integer, OverflowError if out
    of range (negative for an unsigned type included). `name` is used in the message."""
    value = _integer(value, name)
    _check_range(value, *c_range(ctype), name)
    return value


def integer_array(arr, dtype, name, allow_bool=False):
    """Integer ndarray `arr` converted to `dtype` (a numpy integer type) only if every value fits:
    OverflowError otherwise, ValueError for non-integer data. Object arrays of Python ints (numpy's
    choice for values beyond 64 bits) are checked element by element."""
    kinds = "iub" if allow_bool else "iu"
    if arr.size == 0:
        return np.ascontiguousarray(arr, dtype=dtype)
    if arr.dtype.kind == "O":
        if not all(isinstance(v, (int, np.integer)) and (allow_bool or not isinstance(v, bool))
                   for v in arr.flat):
            raise ValueError("%s must hold integers, got dtype object" % name)
    elif arr.dtype.kind not in kinds:
        raise ValueError("%s must hold integers, got dtype %s" % (name, arr.dtype))
    if arr.dtype != dtype:
        info = np.iinfo(dtype)
        # Python ints: exact for uint64 and object arrays, where numpy would compare in float64.
        lo, hi = int(arr.min()), int(arr.max())
        bad = lo if lo < info.min else hi
        _check_range(bad, int(info.min), int(info.max), "%s: value" % name)
    return np.ascontiguousarray(arr, dtype=dtype)


def c_string(value, name):
    """bytes for a char* parameter: a NUL inside would end the string early in C."""
    if isinstance(value, bytes) and b"\0" in value:
        raise ValueError("%s contains a NUL byte" % name)
    return value
