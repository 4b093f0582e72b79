"""numpy <-> C buffer plumbing: input validation and the size-query getter pattern."""
import ctypes
from ctypes import POINTER, c_double, c_int32, c_int64

import numpy as np

from .errors import check

_INT32_MAX = np.iinfo(np.int32).max
_INT32_MIN = np.iinfo(np.int32).min


def ptr(array, ctype):
    """Pointer to a contiguous array's data, or NULL for None."""
    if array is None:
        return None
    return array.ctypes.data_as(POINTER(ctype))


def rows(values, width, dtype, name):
    """`values` as a C-contiguous (n, width) array of `dtype`, copied at most once."""
    arr = np.asarray(values)
    if arr.ndim == 1 and width == 1:
        arr = arr.reshape(-1, 1)
    if arr.ndim != 2 or arr.shape[1] != width:
        raise ValueError("%s must have shape (n, %d), got %s" % (name, width, arr.shape))
    if np.dtype(dtype).kind in "iu" and arr.size and arr.dtype.kind not in "iu":
        raise ValueError("%s must hold integers, got dtype %s" % (name, arr.dtype))
    return np.ascontiguousarray(arr, dtype=dtype)


def indices(values, width, name):
    """Index array as int32 or int64 without copying either; other integer types go to int32."""
    arr = np.asarray(values)
    if arr.dtype == np.int64:
        return rows(arr, width, np.int64, name)
    out = rows(arr, width, np.int32, name) if arr.dtype == np.int32 else None
    if out is None:
        checked = rows(arr, width, np.int64, name)
        if checked.size and (checked.max() > _INT32_MAX or checked.min() < _INT32_MIN):
            raise ValueError("%s: index values must fit in int32" % name)
        out = checked.astype(np.int32)
    return out


def int32_list(values, name):
    """A 1-D int32 array (for chains, uses, edge lists)."""
    arr = np.asarray(values)
    if arr.ndim != 1:
        arr = arr.reshape(-1)
    if arr.size and arr.dtype.kind not in "iub":
        raise ValueError("%s must hold integers, got dtype %s" % (name, arr.dtype))
    if arr.size and (arr.max() > _INT32_MAX or arr.min() < _INT32_MIN):
        raise ValueError("%s: values must fit in int32" % name)
    return np.ascontiguousarray(arr, dtype=np.int32)


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
