"""Solve and meshing options as keyword arguments over the wefm_options / wefm_mesh_options structs.

Defaults always come from the library's *_init functions, never from this file.
Enum-valued fields also accept their names ("rollout", "eigen", "periodic", "transfinite",
"quad-dominant") and flag fields accept bool. Integer fields refuse what their C type cannot hold (OverflowError) and
non-integers (TypeError) instead of letting ctypes wrap or truncate them.
"""
import ctypes

from . import _structs as S
from ._api import lib
from ._checked import C_INTEGERS, c_integer
from ._records import initialised, struct_to_dict

# wefm_edge_mode by value: EDGE_MODE_NAMES[S.EDGE_PERIODIC] == "periodic".
EDGE_MODE_NAMES = ("auto", "free", "periodic", "scar", "rotational")

_ENUMS = {
    "method": {"global": S.METHOD_GLOBAL, "rollout": S.METHOD_ROLLOUT},
    "solver": {"auto": S.SOLVER_AUTO, "cholmod": S.SOLVER_CHOLMOD, "eigen": S.SOLVER_EIGEN},
    "default_edge_mode": {n: i for i, n in enumerate(EDGE_MODE_NAMES)},
    "type": {"free": S.MESH_FREE, "transfinite": S.MESH_TRANSFINITE, "auto": S.MESH_AUTO},
    "elements": {"tri": S.ELEMENTS_TRIANGLES, "triangles": S.ELEMENTS_TRIANGLES, "quad-dominant": S.ELEMENTS_QUAD_DOMINANT,
                 "quad": S.ELEMENTS_QUADS, "quads": S.ELEMENTS_QUADS},
    "residual": {"half-edge": S.RESIDUAL_PER_HALF_EDGE, "use": S.RESIDUAL_PER_USE},
}


def edge_mode_value(mode):
    """An edge mode given as int or name ("periodic") -> int."""
    if isinstance(mode, str):
        try:
            return EDGE_MODE_NAMES.index(mode.lower())
        except ValueError:
            raise ValueError("unknown edge mode %r; one of %s" % (mode, ", ".join(EDGE_MODE_NAMES)))
    return mode  # range-checked with the call (_checked)


def _field_value(ctype, value, what):
    """value as `ctype` stores it: integers range-checked (_checked), arrays element by element."""
    if issubclass(ctype, ctypes.Array):
        if len(value) != ctype._length_:
            raise ValueError("%s needs %d values" % (what, ctype._length_))
        return ctype(*(_field_value(ctype._type_, v, "%s[%d]" % (what, i)) for i, v in enumerate(value)))
    if ctype in C_INTEGERS:
        return c_integer(value, ctype, what)
    return value


def _assign(struct, name, value):
    fields = dict(struct._fields_)
    fields.pop("struct_size")
    if name not in fields:
        raise TypeError("unknown option %r; valid: %s" % (name, ", ".join(fields)))
    if name in _ENUMS and isinstance(value, str):
        try:
            value = _ENUMS[name][value.lower()]
        except KeyError:
            raise ValueError("%s=%r: one of %s" % (name, value, ", ".join(_ENUMS[name])))
    setattr(struct, name, _field_value(fields[name], value, "%s.%s" % (type(struct).__name__, name)))


class _StructOptions:
    _struct_cls = None
    _init = None

    def __init__(self, **kwargs):
        object.__setattr__(self, "_struct", initialised(self._struct_cls, getattr(lib, self._init)))
        for name, value in kwargs.items():
            _assign(self._struct, name, value)

    @classmethod
    def _wrap(cls, struct):
        out = cls()
        ctypes.memmove(ctypes.byref(out._struct), ctypes.byref(struct), ctypes.sizeof(cls._struct_cls))
        out._struct.struct_size = ctypes.sizeof(cls._struct_cls)
        return out

    def __getattr__(self, name):
        struct = object.__getattribute__(self, "_struct")
        if name in (f for f, _ in struct._fields_):
            value = getattr(struct, name)
            return tuple(value) if isinstance(value, ctypes.Array) else value
        raise AttributeError(name)

    def __setattr__(self, name, value):
        _assign(self._struct, name, value)

    def update(self, **kwargs):
        for name, value in kwargs.items():
            _assign(self._struct, name, value)
        return self

    def as_dict(self):
        return struct_to_dict(self._struct)

    def __repr__(self):
        return "%s(%s)" % (type(self).__name__,
                           ", ".join("%s=%r" % kv for kv in self.as_dict().items()))

    def __eq__(self, other):
        return type(other) is type(self) and other.as_dict() == self.as_dict()

    # By value (field names, not the struct's bytes), so a copy never shares the struct with its
    # original and a pickle outlives a change of the struct layout.
    def __reduce__(self):
        return (_rebuild, (type(self), self.as_dict()))

    def __copy__(self):
        return type(self)._wrap(self._struct)

    def __deepcopy__(self, _memo):
        return self.__copy__()


def _rebuild(cls, fields):
    return cls(**fields)


class Options(_StructOptions):
    """wefm_options: Options(s=0.5, method="rollout"); attributes read and write the fields."""
    _struct_cls = S.Options
    _init = "options_init"


class MeshOptions(_StructOptions):
    """wefm_mesh_options: MeshOptions(size=0.05, type="transfinite")."""
    _struct_cls = S.MeshOptions
    _init = "mesh_options_init"
