"""numpy <-> C buffer plumbing: input validation and the size-query getter pattern."""
import ctypes
from ctypes import POINTER, c_double, c_int32, c_int64

import numpy as np

from ._checked import integer_array
from .errors import check


def ptr(array, ctype):
    """Pointer to a contiguous array's data, or NULL for None."""
    if array is None:
        return None
    return array.ctypes.data_as(POINTER(ctype))


def rows(values, width, dtype, name):
    """`values` as a C-contiguous (n, width) array of `dtype`, copied at most once. Integer data is
    converted only if every value fits `dtype` (_checked.integer_array)."""
    arr = np.asarray(values)
    if arr.size == 0:
        # An empty list, or np.loadtxt of a file holding only comments (shape (0, 1)): no rows.
        arr = arr.reshape(0, width)
    if arr.ndim == 1 and width == 1:
        arr = arr.reshape(-1, 1)
    if arr.ndim != 2 or arr.shape[1] != width:
        raise ValueError("%s must have shape (n, %d), got %s" % (name, width, arr.shape))
    if np.dtype(dtype).kind in "iu":
        return integer_array(arr, dtype, name)
    return np.ascontiguousarray(arr, dtype=dtype)


def indices(values, width, name):
    """Index array as int32 or int64 without copying either; other integer types go to int32."""
    arr = np.asarray(values)
    return rows(arr, width, np.int64 if arr.dtype == np.int64 else np.int32, name)


def int32_list(values, name):
    """A 1-D int32 array (for chains, uses, edge lists)."""
    return integer_array(np.asarray(values).reshape(-1), np.int32, name)


_CTYPE = {np.float64: c_double, np.int32: c_int32}


def query(fn, leading, dtype, width=1, handle=None, name=""):
    """Call a getter fn(*leading, buffer, capacity, *count) once with NULL for the size, then with a
    buffer of that many elements. Returns shape (count // width, width), or 1-D when width == 1.
    `handle` is the face whose message explains a failure (None: use wefm_last_error()).
    """
    count = c_int64(0)
    check(fn(*leading, None, 0, ctypes.byref(count)), handle, name)
    out = np.empty(count.value, dtype=dtype)
    check(fn(*leading, ptr(out, _CTYPE[dtype]), count.value, ctypes.byref(count)), handle, name)
    return out if width == 1 else out.reshape(-1, width)
