"""argtypes/restype of every function in wefm.h, applied to the loaded library.

Handles are passed as c_void_p. Every integer and char* argument is checked before ctypes converts it
(_checked: ctypes would wrap 2**32 + 3 to 3), with the parameter's name from the header in the message. A symbol the loaded library does not export (an older or partial
build) becomes a stub raising NotImplementedError when called, so the rest of the API stays usable.
tests/python/test_api_coverage.py checks this table against the header.
"""
import ctypes
from ctypes import POINTER, c_char_p, c_double, c_int, c_int32, c_int64, c_size_t, c_void_p

from . import _loader
from ._checked import C_INTEGERS, c_integer, c_string
from ._structs import MeshInfo, MeshOptions, MeshReport, Options, Report

# int (*wefm_progress_fn)(void* user_data, double fraction, const char* stage)
PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, c_double, c_char_p)

_d = POINTER(c_double)
_i32 = POINTER(c_int32)
_i64 = POINTER(c_int64)
_vpp = POINTER(c_void_p)
_S = c_int  # wefm_status: a C enum, int-sized on every ABI we target

# name (without the wefm_ prefix): (restype, "parameter names as in wefm.h", [argtypes])
PROTOTYPES = {
    "status_string": (c_char_p, "status", [c_int]),
    "last_error": (c_char_p, "", []),
    "version": (c_char_p, "", []),
    "version_number": (c_int, "", []),
    "has_suitesparse": (c_int, "", []),
    "options_init": (_S, "options struct_size", [POINTER(Options), c_size_t]),
    # meshes read from files
    "mesh_info_init": (_S, "info struct_size", [POINTER(MeshInfo), c_size_t]),
    "mesh_read": (_S, "path merge_tolerance out", [c_char_p, c_double, _vpp]),
    "mesh_create": (_S, "vertex_count xyz triangle_count triangles out", [c_int64, _d, c_int64, _i32, _vpp]),
    "mesh_retain": (_S, "mesh", [c_void_p]),
    "mesh_release": (None, "mesh", [c_void_p]),
    "mesh_get_vertices": (_S, "mesh xyz capacity count", [c_void_p, _d, c_int64, _i64]),
    "mesh_get_triangles": (_S, "mesh tri capacity count", [c_void_p, _i32, c_int64, _i64]),
    "mesh_get_info": (_S, "mesh info", [c_void_p, POINTER(MeshInfo)]),
    # faces
    "face_create": (_S, "out", [_vpp]),
    "face_retain": (_S, "face", [c_void_p]),
    "face_release": (None, "face", [c_void_p]),
    "face_last_error": (c_char_p, "face", [c_void_p]),
    "face_set_mesh": (_S, "face vertex_count xyz triangle_count triangles",
                      [c_void_p, c_int64, _d, c_int64, _i32]),
    "face_set_mesh_i64": (_S, "face vertex_count xyz triangle_count triangles",
                          [c_void_p, c_int64, _d, c_int64, _i64]),
    "face_set_mesh_from": (_S, "face mesh", [c_void_p, c_void_p]),
    "face_set_options": (_S, "face options", [c_void_p, POINTER(Options)]),
    "face_get_options": (_S, "face options", [c_void_p, POINTER(Options)]),
    # topology
    "face_clear_topology": (_S, "face", [c_void_p]),
    "face_add_edge": (_S, "face n chain edge_id", [c_void_p, c_int64, _i32, _i32]),
    "face_add_loop": (_S, "face n edges reversed loop_id", [c_void_p, c_int64, _i32, _i32, _i32]),
    "face_set_outer_loop": (_S, "face loop", [c_void_p, c_int32]),
    "face_add_seams": (_S, "face n vertex_pairs", [c_void_p, c_int64, _i32]),
    "face_set_edge_mode": (_S, "face edge mode", [c_void_p, c_int32, c_int]),
    "face_build": (_S, "face", [c_void_p]),
    "face_edge_count": (_S, "face count", [c_void_p, _i64]),
    "face_get_edge": (_S, "face edge chain capacity count", [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_edge_is_repeated": (_S, "face edge repeated", [c_void_p, c_int32, _i32]),
    "face_loop_count": (_S, "face count", [c_void_p, _i64]),
    "face_get_loop": (_S, "face loop edge_uses capacity count", [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_get_loop_uses": (_S, "face loop uses capacity count", [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_outer_loop": (_S, "face loop", [c_void_p, _i32]),
    # vertex uses
    "face_use_count": (_S, "face count", [c_void_p, _i64]),
    "face_get_use_vertices": (_S, "face vertices capacity count", [c_void_p, _i32, c_int64, _i64]),
    "face_get_triangle_uses": (_S, "face uses capacity count", [c_void_p, _i32, c_int64, _i64]),
    "face_get_vertex_uses": (_S, "face vertex uses capacity count", [c_void_p, c_int32, _i32, c_int64, _i64]),
    # constraints
    "face_add_pin": (_S, "face use u v constraint_id", [c_void_p, c_int32, c_double, c_double, _i32]),
    "face_add_constraint": (_S, "face n uses coefficients rhs constraint_id",
                            [c_void_p, c_int64, _i32, _d, _d, _i32]),
    "face_clear_constraints": (_S, "face", [c_void_p]),
    # solving
    "face_set_progress_callback": (_S, "face fn user_data", [c_void_p, PROGRESS_FN, c_void_p]),
    "face_solve": (_S, "face", [c_void_p]),
    "face_cancel": (_S, "face", [c_void_p]),
    "face_has_result": (_S, "face solved", [c_void_p, _i32]),
    # results
    "face_get_uv": (_S, "face uv capacity count", [c_void_p, _d, c_int64, _i64]),
    "face_get_edge_modes": (_S, "face modes capacity count", [c_void_p, _i32, c_int64, _i64]),
    "face_get_edge_scores": (_S, "face edge scores capacity count", [c_void_p, c_int32, _d, c_int64, _i64]),
    "report_init": (_S, "report struct_size", [POINTER(Report), c_size_t]),
    "face_get_report": (_S, "face report", [c_void_p, POINTER(Report)]),
    "face_get_step_history": (_S, "face steps capacity count", [c_void_p, _d, c_int64, _i64]),
    # mapping and output
    "face_map_uv_to_3d": (_S, "face n uv xyz point_status triangles",
                          [c_void_p, c_int64, _d, _d, _i32, _i32]),
    "face_map_3d_to_uv": (_S, "face n xyz uv point_status triangles",
                          [c_void_p, c_int64, _d, _d, _i32, _i32]),
    "face_write_obj": (_S, "face path", [c_void_p, c_char_p]),
    # meshing the domain
    "mesh_options_init": (_S, "options struct_size", [POINTER(MeshOptions), c_size_t]),
    "mesh_report_init": (_S, "report struct_size", [POINTER(MeshReport), c_size_t]),
    "face_set_edge_nodes": (_S, "face edge n xyz", [c_void_p, c_int32, c_int64, _d]),
    "face_clear_edge_nodes": (_S, "face", [c_void_p]),
    "face_mesh_domain": (_S, "face options out", [c_void_p, POINTER(MeshOptions), _vpp]),
    "domain_mesh_retain": (_S, "mesh", [c_void_p]),
    "domain_mesh_release": (None, "mesh", [c_void_p]),
    "domain_mesh_get_uv": (_S, "mesh uv capacity count", [c_void_p, _d, c_int64, _i64]),
    "domain_mesh_get_xyz": (_S, "mesh xyz capacity count", [c_void_p, _d, c_int64, _i64]),
    "domain_mesh_get_elements": (_S, "mesh nodes capacity count", [c_void_p, _i32, c_int64, _i64]),
    "domain_mesh_get_report": (_S, "mesh report", [c_void_p, POINTER(MeshReport)]),
    "domain_mesh_write_obj": (_S, "mesh path", [c_void_p, c_char_p]),
}


def _checked(fn, name, params, argtypes):
    """fn with its integer and char* arguments checked first (a plain call when it has none)."""
    names = params.split()
    ints = [(i, "wefm_%s: %s" % (name, names[i]), t) for i, t in enumerate(argtypes) if t in C_INTEGERS]
    strings = [(i, "wefm_%s: %s" % (name, names[i])) for i, t in enumerate(argtypes) if t is c_char_p]
    if not ints and not strings:
        return fn

    def call(*args):
        args = list(args)
        for i, what, ctype in ints:
            if i < len(args):  # a wrong count is left to ctypes' own TypeError
                args[i] = c_integer(args[i], ctype, what)
        for i, what in strings:
            if i < len(args):
                c_string(args[i], what)
        return fn(*args)

    call.__name__ = "wefm_" + name
    call.raw = fn
    return call


def _missing(name, path):
    def stub(*_args):
        raise NotImplementedError("the loaded libwefm (%s) does not export wefm_%s" % (path, name))
    stub.missing = True
    return stub


class _Lib:
    """The library with short names: lib.face_solve(h) calls wefm_face_solve(h)."""

    def __init__(self, cdll, path):
        self.cdll = cdll
        self.path = path
        self.missing = []
        for name, (restype, params, argtypes) in PROTOTYPES.items():
            try:
                fn = getattr(cdll, "wefm_" + name)
            except AttributeError:
                self.missing.append("wefm_" + name)
                setattr(self, name, _missing(name, path))
                continue
            fn.restype = restype
            fn.argtypes = argtypes
            setattr(self, name, _checked(fn, name, params, argtypes))


lib = _Lib(*_loader.load())
