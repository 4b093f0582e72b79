"""argtypes/restype of every function in wefm.h, applied to the loaded library.

Handles are passed as c_void_p. A symbol the loaded library does not export (an older or partial
build) becomes a stub raising NotImplementedError when called, so the rest of the API stays usable.
tests/python/test_api_coverage.py checks this table against the header.
"""
import ctypes
from ctypes import POINTER, c_char_p, c_double, c_int, c_int32, c_int64, c_size_t, c_void_p

from . import _loader
from ._structs import MeshInfo, MeshOptions, MeshReport, Options, Report

# int (*wefm_progress_fn)(void* user_data, double fraction, const char* stage)
PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, c_double, c_char_p)

_d = POINTER(c_double)
_i32 = POINTER(c_int32)
_i64 = POINTER(c_int64)
_vpp = POINTER(c_void_p)
_S = c_int  # wefm_status: a C enum, int-sized on every ABI we target

# name (without the wefm_ prefix): (restype, [argtypes])
PROTOTYPES = {
    "status_string": (c_char_p, [c_int]),
    "last_error": (c_char_p, []),
    "version": (c_char_p, []),
    "version_number": (c_int, []),
    "has_suitesparse": (c_int, []),
    "options_init": (_S, [POINTER(Options), c_size_t]),
    # meshes read from files
    "mesh_info_init": (_S, [POINTER(MeshInfo), c_size_t]),
    "mesh_read": (_S, [c_char_p, c_double, _vpp]),
    "mesh_create": (_S, [c_int64, _d, c_int64, _i32, _vpp]),
    "mesh_retain": (_S, [c_void_p]),
    "mesh_release": (None, [c_void_p]),
    "mesh_get_vertices": (_S, [c_void_p, _d, c_int64, _i64]),
    "mesh_get_triangles": (_S, [c_void_p, _i32, c_int64, _i64]),
    "mesh_get_info": (_S, [c_void_p, POINTER(MeshInfo)]),
    # faces
    "face_create": (_S, [_vpp]),
    "face_retain": (_S, [c_void_p]),
    "face_release": (None, [c_void_p]),
    "face_last_error": (c_char_p, [c_void_p]),
    "face_set_mesh": (_S, [c_void_p, c_int64, _d, c_int64, _i32]),
    "face_set_mesh_i64": (_S, [c_void_p, c_int64, _d, c_int64, _i64]),
    "face_set_mesh_from": (_S, [c_void_p, c_void_p]),
    "face_set_options": (_S, [c_void_p, POINTER(Options)]),
    "face_get_options": (_S, [c_void_p, POINTER(Options)]),
    # topology
    "face_clear_topology": (_S, [c_void_p]),
    "face_add_edge": (_S, [c_void_p, c_int64, _i32, _i32]),
    "face_add_loop": (_S, [c_void_p, c_int64, _i32, _i32, _i32]),
    "face_set_outer_loop": (_S, [c_void_p, c_int32]),
    "face_add_seams": (_S, [c_void_p, c_int64, _i32]),
    "face_set_edge_mode": (_S, [c_void_p, c_int32, c_int]),
    "face_build": (_S, [c_void_p]),
    "face_edge_count": (_S, [c_void_p, _i64]),
    "face_get_edge": (_S, [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_edge_is_repeated": (_S, [c_void_p, c_int32, _i32]),
    "face_loop_count": (_S, [c_void_p, _i64]),
    "face_get_loop": (_S, [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_get_loop_uses": (_S, [c_void_p, c_int32, _i32, c_int64, _i64]),
    "face_outer_loop": (_S, [c_void_p, _i32]),
    # vertex uses
    "face_use_count": (_S, [c_void_p, _i64]),
    "face_get_use_vertices": (_S, [c_void_p, _i32, c_int64, _i64]),
    "face_get_triangle_uses": (_S, [c_void_p, _i32, c_int64, _i64]),
    "face_get_vertex_uses": (_S, [c_void_p, c_int32, _i32, c_int64, _i64]),
    # constraints
    "face_add_pin": (_S, [c_void_p, c_int32, c_double, c_double, _i32]),
    "face_add_constraint": (_S, [c_void_p, c_int64, _i32, _d, _d, _i32]),
    "face_clear_constraints": (_S, [c_void_p]),
    # solving
    "face_set_progress_callback": (_S, [c_void_p, PROGRESS_FN, c_void_p]),
    "face_solve": (_S, [c_void_p]),
    "face_cancel": (_S, [c_void_p]),
    "face_has_result": (_S, [c_void_p, _i32]),
    # results
    "face_get_uv": (_S, [c_void_p, _d, c_int64, _i64]),
    "face_get_edge_modes": (_S, [c_void_p, _i32, c_int64, _i64]),
    "face_get_edge_scores": (_S, [c_void_p, c_int32, _d, c_int64, _i64]),
    "report_init": (_S, [POINTER(Report), c_size_t]),
    "face_get_report": (_S, [c_void_p, POINTER(Report)]),
    "face_get_step_history": (_S, [c_void_p, _d, c_int64, _i64]),
    # mapping and output
    "face_map_uv_to_3d": (_S, [c_void_p, c_int64, _d, _d, _i32, _i32]),
    "face_map_3d_to_uv": (_S, [c_void_p, c_int64, _d, _d, _i32, _i32]),
    "face_write_obj": (_S, [c_void_p, c_char_p]),
    # meshing the domain
    "mesh_options_init": (_S, [POINTER(MeshOptions), c_size_t]),
    "mesh_report_init": (_S, [POINTER(MeshReport), c_size_t]),
    "face_set_edge_nodes": (_S, [c_void_p, c_int32, c_int64, _d]),
    "face_clear_edge_nodes": (_S, [c_void_p]),
    "face_mesh_domain": (_S, [c_void_p, POINTER(MeshOptions), _vpp]),
    "domain_mesh_retain": (_S, [c_void_p]),
    "domain_mesh_release": (None, [c_void_p]),
    "domain_mesh_get_uv": (_S, [c_void_p, _d, c_int64, _i64]),
    "domain_mesh_get_xyz": (_S, [c_void_p, _d, c_int64, _i64]),
    "domain_mesh_get_elements": (_S, [c_void_p, _i32, c_int64, _i64]),
    "domain_mesh_get_report": (_S, [c_void_p, POINTER(MeshReport)]),
    "domain_mesh_write_obj": (_S, [c_void_p, c_char_p]),
}


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
        for name, (restype, argtypes) in PROTOTYPES.items():
            try:
                fn = getattr(cdll, "wefm_" + name)
            except AttributeError:
                self.missing.append("wefm_" + name)
                setattr(self, name, _missing(name, path))
                continue
            fn.restype = restype
            fn.argtypes = argtypes
            setattr(self, name, fn)


lib = _Lib(*_loader.load())
