"""ctypes mirrors of the structs and enums of wefm.h.

Fields are in header order and must stay that way: the library reads these structs by layout.
A test compares every offset with what a C compiler produces (tests/python/test_layout.py).
"""
import ctypes
from ctypes import c_double, c_int, c_int32, c_int64, c_size_t

# wefm_status
OK = 0
ERROR_NULL_ARGUMENT = 1
ERROR_INVALID_ARGUMENT = 2
ERROR_OUT_OF_RANGE = 3
ERROR_BUFFER_TOO_SMALL = 4
ERROR_INVALID_STATE = 5
ERROR_INVALID_MESH = 6
ERROR_INVALID_TOPOLOGY = 7
ERROR_INVALID_CONSTRAINT = 8
ERROR_SINGULAR = 9
ERROR_NOT_POSITIVE_DEFINITE = 10
ERROR_NOT_CONVERGED = 11
ERROR_CANCELLED = 12
ERROR_OUT_OF_MEMORY = 13
ERROR_IO = 14
ERROR_UNSUPPORTED = 15
ERROR_OUTSIDE_DOMAIN = 16
ERROR_INTERNAL = 99

# wefm_method
METHOD_GLOBAL = 0
METHOD_ROLLOUT = 1

# wefm_residual
RESIDUAL_PER_HALF_EDGE = 0
RESIDUAL_PER_USE = 1

# wefm_edge_mode
EDGE_AUTO = 0
EDGE_FREE = 1
EDGE_PERIODIC = 2
EDGE_SCAR = 3
EDGE_ROTATIONAL = 4
EDGE_MODE_NAMES = ("auto", "free", "periodic", "scar", "rotational")

# wefm_solver
SOLVER_AUTO = 0
SOLVER_CHOLMOD = 1
SOLVER_EIGEN = 2

# wefm_mesh_type
MESH_FREE = 0
MESH_TRANSFINITE = 1


class Options(ctypes.Structure):
    """struct wefm_options."""
    _fields_ = [
        ("struct_size", c_size_t),
        ("s", c_double),
        ("k", c_double),
        ("boundary_weight", c_double),
        ("curvature_adjust", c_int),
        ("method", c_int),
        ("solver", c_int),
        ("default_edge_mode", c_int),
        ("s_step", c_double),
        ("rho_tolerance", c_double),
        ("max_rho_iterations", c_int),
        ("rollout_tolerance", c_double),
        ("max_rollout_sweeps", c_int),
        ("score_threshold", c_double),
        ("auto_cut", c_int),
        ("threads", c_int),
        ("memory_limit_mb", c_double),
        ("min_beta", c_double),
        ("residual", c_int),
    ]


class MeshInfo(ctypes.Structure):
    """struct wefm_mesh_info."""
    _fields_ = [
        ("struct_size", c_size_t),
        ("vertices", c_int64),
        ("triangles", c_int64),
        ("boundary_loops", c_int64),
        ("components", c_int64),
        ("genus", c_int64),
        ("non_manifold_edges", c_int64),
        ("non_manifold_vertices", c_int64),
        ("degenerate_triangles", c_int64),
        ("duplicate_triangles", c_int64),
        ("inconsistent_edges", c_int64),
        ("merged_vertices", c_int64),
        ("bbox_min", c_double * 3),
        ("bbox_max", c_double * 3),
        ("area", c_double),
        ("mean_edge_length", c_double),
    ]


class Report(ctypes.Structure):
    """struct wefm_report."""
    _fields_ = [
        ("struct_size", c_size_t),
        ("score", c_double),
        ("flipped_triangles", c_int64),
        ("boundary_intersections", c_int64),
        ("area_distortion_mean", c_double),
        ("area_distortion_max", c_double),
        ("angle_distortion_mean", c_double),
        ("angle_distortion_max", c_double),
        ("uv_area", c_double),
        ("area_3d", c_double),
        ("s", c_double),
        ("converged", c_int32),
        ("method", c_int32),
        ("s_steps", c_int32),
        ("rho_iterations", c_int32),
        ("rho_change", c_double),
        ("symbolic_analyses", c_int64),
        ("numeric_factorizations", c_int64),
        ("solves", c_int64),
        ("iterative_iterations", c_int64),
        ("auto_cut", c_int32),
        ("degenerate_triangles", c_int32),
        ("time_topology", c_double),
        ("time_coefficients", c_double),
        ("time_assembly", c_double),
        ("time_analysis", c_double),
        ("time_factorization", c_double),
        ("time_solve", c_double),
        ("time_continuation", c_double),
        ("time_quality", c_double),
        ("time_total", c_double),
        ("peak_memory_mb", c_double),
        ("min_beta_raised", c_int32),
        ("boundary_unwind", c_double),
        ("auto_cut_edges", c_int32),
        ("auto_cut_uncut_kept", c_int32),
        ("auto_cut_length", c_double),
        ("auto_cut_other_score", c_double),
        ("via_s", c_double),
        ("boundary_unwind_weight", c_double),
        ("abandoned_steps", c_int32),
    ]


class MeshOptions(ctypes.Structure):
    """struct wefm_mesh_options."""
    _fields_ = [
        ("struct_size", c_size_t),
        ("type", c_int),
        ("size", c_double),
        ("corners", c_int32 * 4),
        ("quads", c_int),
        ("smoothing_iterations", c_int),
        ("corner_angle_deg", c_double),
        ("min_angle_deg", c_double),
        ("max_elements", c_int64),
    ]


class MeshReport(ctypes.Structure):
    """struct wefm_mesh_report."""
    _fields_ = [
        ("struct_size", c_size_t),
        ("nodes", c_int64),
        ("elements", c_int64),
        ("nodes_per_element", c_int32),
        ("lambda_mesh", c_double),
        ("lambda_min", c_double),
        ("fraction_below_0_6", c_double),
        ("scaled_jacobian_min", c_double),
        ("scaled_jacobian_mean", c_double),
        ("wiggle_max", c_double),
        ("wiggle_mean", c_double),
        ("time_boundary", c_double),
        ("time_mesh", c_double),
        ("time_smooth", c_double),
        ("time_map", c_double),
    ]


def struct_to_dict(struct):
    """Plain-Python copy of a struct's fields (arrays become tuples), without struct_size."""
    out = {}
    for name, _ in struct._fields_:
        if name == "struct_size":
            continue
        value = getattr(struct, name)
        out[name] = tuple(value) if isinstance(value, ctypes.Array) else value
    return out
