"""Face methods for linear constraints on the complex unknowns z = u + i v."""
import ctypes
from ctypes import c_double, c_int32

import numpy as np

from ._arrays import int32_list, ptr


def _point(u, v):
    """(u, v) from a complex, a pair, or two reals."""
    if v is None:
        if isinstance(u, (complex, np.complexfloating)):
            return float(u.real), float(u.imag)
        u, v = u
    return float(u), float(v)


class ConstraintsMixin:
    def add_pin(self, use, u, v=None):
        """Pin a use at (u, v); u may be a complex or a pair instead. Returns the constraint id."""
        u, v = _point(u, v)
        cid = c_int32(-1)
        self._call("face_add_pin", use, u, v, ctypes.byref(cid))
        return cid.value

    def add_constraint(self, uses, coefficients, rhs=0j):
        """Add sum_j coefficients[j] * z[uses[j]] = rhs. Coefficients and rhs are Python complex,
        numpy complex128 or reals. Returns the constraint id."""
        uses = int32_list(uses, "uses")
        # complex128 is laid out (re, im) like the C API's double pairs: a view, no repacking.
        coef = np.ascontiguousarray(np.asarray(coefficients, dtype=np.complex128).reshape(-1))
        if coef.size != uses.size:
            raise ValueError("%d coefficients for %d uses" % (coef.size, uses.size))
        pairs = coef.view(np.float64)
        rhs_pair = np.array(_point(complex(rhs), None), dtype=np.float64)
        cid = c_int32(-1)
        self._call("face_add_constraint", uses.size, ptr(uses, c_int32), ptr(pairs, c_double),
                   ptr(rhs_pair, c_double), ctypes.byref(cid))
        return cid.value

    def clear_constraints(self):
        self._call("face_clear_constraints")
