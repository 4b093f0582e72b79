/*
 * wefm.h: the stable C API of wefm, the Weighted Edge Flattening Method library.
 *
 * wefm flattens a 3D triangulated surface (a "facetted face") into a low-distortion 2D domain,
 * meshes that domain and maps the mesh back to 3D.
 *
 * ---------------------------------------------------------------------------------------------
 * Conventions (followed by every function in this header)
 * ---------------------------------------------------------------------------------------------
 * Status.      Every function that can fail returns a wefm_status; WEFM_OK is 0. wefm_status_string()
 *              names a code. Functions never abort, never throw and never call exit().
 * Messages.    A failing call on a handle stores a detailed message (which index, which loop) on that
 *              handle: wefm_face_last_error(). Failures with no handle (creation, NULL handle, file
 *              reading) store a thread-local message: wefm_last_error(). Both are overwritten by the
 *              next failing call and stay valid until then.
 * NULL.        Every function accepts NULL handles and NULL pointers and returns
 *              WEFM_ERROR_NULL_ARGUMENT instead of crashing (release functions accept NULL silently).
 * Buffers.     Output arrays are owned by the caller. A getter takes (buffer, capacity, *count):
 *              `capacity` and `*count` are numbers of array ELEMENTS (doubles or integers, not items).
 *              Call with buffer = NULL to learn the size: *count is set and WEFM_OK returned. When
 *              capacity < *count, nothing is written and WEFM_ERROR_BUFFER_TOO_SMALL is returned with
 *              *count set. So Fortran and ctypes callers never free library memory.
 * Inputs.      Input arrays are copied before the call returns; they are never retained or modified.
 * Indices.     0-based. Counts and capacities are int64_t. Element indices passed in arrays are
 *              int32_t (a face holds at most 2^31-1 vertices, triangles and uses); functions with
 *              the suffix _i64 take int64_t index arrays (values must still fit in int32_t).
 * Complex.     A point of the domain is z = u + i v. Complex numbers are passed as two doubles (re, im).
 * Handles.     Opaque and reference counted (as Embree): *_create returns a handle with count 1,
 *              *_retain adds one, *_release drops one and frees at zero.
 * Threads.     Distinct handles may be used concurrently from different threads. One handle must not
 *              be used from two threads at once, with one exception: wefm_face_cancel() may be called
 *              from any thread while wefm_face_solve()/wefm_face_mesh_domain() runs on another.
 *              The library starts no threads of its own unless wefm_options.threads > 1.
 * Exceptions.  None cross this boundary. Memory exhaustion returns WEFM_ERROR_OUT_OF_MEMORY.
 * Invalidation. Setting a new mesh clears topology, constraints and results. Changing topology or
 *              constraints clears results. A failed or cancelled solve keeps the previous result.
 *
 * ABI.         Structs that may grow (wefm_options, wefm_report, wefm_mesh_options,
 *              wefm_mesh_report, wefm_mesh_info) start with `struct_size`. Their *_init function
 *              takes the size of the struct as the CALLER compiled it:
 *                  wefm_options o; wefm_options_init(&o, sizeof o);
 *              (C++ may write wefm_options_init(&o): inline overloads at the end of this header
 *              pass the size). Init writes the library's defaults into those bytes only (zeroing
 *              any tail the library does not know) and sets struct_size to the caller's size; every
 *              later call reads and writes only the first struct_size bytes. So a program built
 *              against an older header, with a smaller struct, gets defaults for the fields it does
 *              not know and is never overrun; fields newer than the loaded library are ignored
 *              (check wefm_version_number() if one matters). Always call the *_init function first:
 *              struct_size < sizeof(size_t) (e.g. a zeroed struct) is rejected.
 *              Why the explicit size: an init writing sizeof(struct) as the LIBRARY was compiled
 *              would overrun an older caller's struct, and only the caller's compiler knows the
 *              caller's size. A static inline init in this header would know it too, but FFI callers
 *              (ctypes, Fortran bind(C)) cannot call inline functions, and the defaults would be
 *              frozen into each caller instead of coming from the library. We chose
 *              init-functions-plus-struct_size over per-option setters because FFI users map a
 *              plain struct directly and get all defaults at once.
 *              Only functions in the stable section keep their ABI across minor versions; the
 *              experimental section (WEFM_EXPERIMENTAL) may change in any release.
 */
#ifndef WEFM_WEFM_H
#define WEFM_WEFM_H

#include <stddef.h>
#include <stdint.h>

#define WEFM_VERSION_MAJOR 0
#define WEFM_VERSION_MINOR 1
#define WEFM_VERSION_PATCH 0
#define WEFM_VERSION_NUMBER (WEFM_VERSION_MAJOR * 10000 + WEFM_VERSION_MINOR * 100 + WEFM_VERSION_PATCH)

#if defined(_WIN32)
#  if defined(WEFM_BUILDING_LIBRARY)
#    define WEFM_API __declspec(dllexport)
#  else
#    define WEFM_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) || defined(__clang__)
#  define WEFM_API __attribute__((visibility("default")))
#else
#  define WEFM_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ============================================================================================= */
/* Status codes                                                                                  */
/* ============================================================================================= */

typedef enum wefm_status {
  WEFM_OK = 0,
  WEFM_ERROR_NULL_ARGUMENT = 1,       /**< a required handle or pointer was NULL */
  WEFM_ERROR_INVALID_ARGUMENT = 2,    /**< an argument has a value outside its domain */
  WEFM_ERROR_OUT_OF_RANGE = 3,        /**< an index is negative or past the end */
  WEFM_ERROR_BUFFER_TOO_SMALL = 4,    /**< capacity < required count; *count holds the size needed */
  WEFM_ERROR_INVALID_STATE = 5,       /**< call out of order: solve before a mesh, query before solve */
  WEFM_ERROR_INVALID_MESH = 6,        /**< NaN, bad indices, degenerate/duplicate/non-manifold input */
  WEFM_ERROR_INVALID_TOPOLOGY = 7,    /**< edges, loops or seams that do not match the mesh */
  WEFM_ERROR_INVALID_CONSTRAINT = 8,  /**< a constraint names an unknown use or has no terms */
  WEFM_ERROR_SINGULAR = 9,            /**< contradictory or insufficient constraints: KKT singular */
  WEFM_ERROR_NOT_POSITIVE_DEFINITE = 10, /**< the energy matrix could not be factorised */
  WEFM_ERROR_NOT_CONVERGED = 11,      /**< an iteration cap was reached; the best result is kept */
  WEFM_ERROR_CANCELLED = 12,          /**< cancelled by wefm_face_cancel() or the progress callback */
  WEFM_ERROR_OUT_OF_MEMORY = 13,      /**< allocation failed or the memory limit would be exceeded */
  WEFM_ERROR_IO = 14,                 /**< a file could not be read or written */
  WEFM_ERROR_UNSUPPORTED = 15,        /**< a format or feature not available in this build */
  WEFM_ERROR_OUTSIDE_DOMAIN = 16,     /**< a point to map lies outside the domain (per point) */
  WEFM_ERROR_INTERNAL = 99            /**< a bug: please report it with the message */
} wefm_status;

/** Name of a status code ("WEFM_OK", ...). Never NULL; unknown codes give "WEFM_ERROR_UNKNOWN". */
WEFM_API const char* wefm_status_string(wefm_status status);

/** Thread-local message of the last failure that had no handle to carry it ("" if none). */
WEFM_API const char* wefm_last_error(void);

/* ============================================================================================= */
/* Version                                                                                       */
/* ============================================================================================= */

/** Run-time version as "MAJOR.MINOR.PATCH". Compare with WEFM_VERSION_* to detect a mismatch. */
WEFM_API const char* wefm_version(void);
/** Run-time version as WEFM_VERSION_NUMBER. */
WEFM_API int wefm_version_number(void);
/** Non-zero if this build factorises with SuiteSparse CHOLMOD, zero for the Eigen-only build. */
WEFM_API int wefm_has_suitesparse(void);

/* ============================================================================================= */
/* Options                                                                                       */
/* ============================================================================================= */

typedef enum wefm_method {
  WEFM_METHOD_GLOBAL = 0,  /**< global least squares with Lagrange constraints (paper §4.2) */
  WEFM_METHOD_ROLLOUT = 1  /**< iterative roll-out with Gauss-Seidel sweeps (paper §4.1) */
} wefm_method;

typedef enum wefm_edge_mode {
  WEFM_EDGE_AUTO = 0,      /**< choose by score (METHOD §7 step 2) */
  WEFM_EDGE_FREE = 1,      /**< the two sides are independent */
  WEFM_EDGE_PERIODIC = 2,  /**< the two sides are translates of each other */
  WEFM_EDGE_SCAR = 3,      /**< the two sides coincide */
  WEFM_EDGE_ROTATIONAL = 4 /**< the two sides are related by a rotation about a free centre */
} wefm_edge_mode;

typedef enum wefm_solver {
  WEFM_SOLVER_AUTO = 0,    /**< CHOLMOD when built with it, else Eigen */
  WEFM_SOLVER_CHOLMOD = 1, /**< SuiteSparse CHOLMOD supernodal Cholesky */
  WEFM_SOLVER_EIGEN = 2    /**< Eigen's SimplicialLDLT (permissive licence) */
} wefm_solver;

typedef struct wefm_options {
  size_t struct_size;        /**< set by wefm_options_init */
  double s;                  /**< target roll-out exponent in [0,2]: 0 conformal, 1 altitude, 2 area. Default 1 */
  double k;                  /**< weight normalisation exponent, 1 or 0.5 (any value in [0,1]). Default 1 */
  double boundary_weight;    /**< mu, dimensionless weight of the boundary term (>= 0). Default 1 */
  int curvature_adjust;      /**< non-zero: scale beta by Theta/2pi at interior uses. Default 1 */
  int method;                /**< wefm_method. Default WEFM_METHOD_GLOBAL */
  int solver;                /**< wefm_solver. Default WEFM_SOLVER_AUTO */
  int default_edge_mode;     /**< wefm_edge_mode for repeated edges not set per edge. Default AUTO */
  double s_step;             /**< largest continuation step in s (0 < s_step <= 2). Default 0.25 */
  double rho_tolerance;      /**< stop the rho fixed point when max relative change < this. Default 1e-3 */
  int max_rho_iterations;    /**< per s step; reaching it reports non-convergence. Default 20 */
  double rollout_tolerance;  /**< roll-out sweep stop: max move / mean edge < this. Default 1e-10 */
  int max_rollout_sweeps;    /**< Default 10000 */
  double score_threshold;    /**< return after the conformal solve if its score >= this. Default 2 (never) */
  int auto_cut;              /**< non-zero: cut annuli and closed surfaces automatically. Default 0 */
  int threads;               /**< worker threads for assembly/quality (0 = 1). Default 0 */
  double memory_limit_mb;    /**< refuse solves estimated above this (0 = no limit). Default 0 */
  double min_beta;           /**< altitude/base floor for degenerate triangles (> 0). Default 1e-3 */
} wefm_options;

/**
 * Fill `options` with the library's defaults (see "ABI" above).
 * @param options      caller-owned; only its first `struct_size` bytes are written.
 * @param struct_size  sizeof(wefm_options) as the caller compiled it.
 * @return WEFM_OK; WEFM_ERROR_NULL_ARGUMENT if `options` is NULL; WEFM_ERROR_INVALID_ARGUMENT if
 *         struct_size < sizeof(size_t). Nothing is written on error; the message is in wefm_last_error().
 */
WEFM_API wefm_status wefm_options_init(wefm_options* options, size_t struct_size);

/* ============================================================================================= */
/* Triangle meshes read from files                                                              */
/* ============================================================================================= */

typedef struct wefm_mesh wefm_mesh;

typedef struct wefm_mesh_info {
  size_t struct_size;
  int64_t vertices, triangles;
  int64_t boundary_loops;        /**< boundary cycles of the triangulation */
  int64_t components;            /**< edge-connected components */
  int64_t genus;                 /**< from Euler characteristic, per the whole mesh; -1 if non-manifold */
  int64_t non_manifold_edges;    /**< edges with more than two triangles */
  int64_t non_manifold_vertices; /**< vertices whose triangle fan is not one disk or half-disk */
  int64_t degenerate_triangles;  /**< zero-area triangles (collinear or repeated vertices) */
  int64_t duplicate_triangles;   /**< triangles on the same three vertices as another */
  int64_t inconsistent_edges;    /**< interior edges whose two triangles disagree in orientation */
  int64_t merged_vertices;       /**< vertices merged while reading (STL) */
  double bbox_min[3], bbox_max[3];
  double area;                   /**< total 3D area */
  double mean_edge_length;
} wefm_mesh_info;

/** Zero `info` and set struct_size = `struct_size` (the caller's sizeof); errors as wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_info_init(wefm_mesh_info* info, size_t struct_size);

/**
 * Read a triangle mesh: OBJ, OFF, STL (ASCII or binary) or PLY, chosen by extension.
 * STL vertices closer than `merge_tolerance` (relative to the bounding-box diagonal; <= 0 uses 1e-9)
 * are merged; the count is in wefm_mesh_info.merged_vertices. Polygons are fan-triangulated.
 * On failure *out is NULL and wefm_last_error() says what is wrong.
 */
WEFM_API wefm_status wefm_mesh_read(const char* path, double merge_tolerance, wefm_mesh** out);
/** Create a mesh from arrays (copied). Indices are checked for range only. */
WEFM_API wefm_status wefm_mesh_create(int64_t vertex_count, const double* xyz, int64_t triangle_count,
                                      const int32_t* triangles, wefm_mesh** out);
WEFM_API wefm_status wefm_mesh_retain(wefm_mesh* mesh);
WEFM_API void wefm_mesh_release(wefm_mesh* mesh);
/** xyz: 3 doubles per vertex. */
WEFM_API wefm_status wefm_mesh_get_vertices(const wefm_mesh* mesh, double* xyz, int64_t capacity, int64_t* count);
/** triangles: 3 int32 per triangle. */
WEFM_API wefm_status wefm_mesh_get_triangles(const wefm_mesh* mesh, int32_t* tri, int64_t capacity, int64_t* count);
/** What a user checks before flattening. */
WEFM_API wefm_status wefm_mesh_get_info(const wefm_mesh* mesh, wefm_mesh_info* info);

/* ============================================================================================= */
/* Faces                                                                                         */
/* ============================================================================================= */

typedef struct wefm_face wefm_face;

WEFM_API wefm_status wefm_face_create(wefm_face** out);
WEFM_API wefm_status wefm_face_retain(wefm_face* face);
WEFM_API void wefm_face_release(wefm_face* face);
/** Detailed message of the last failing call on this face ("" if none). Valid until the next call. */
WEFM_API const char* wefm_face_last_error(const wefm_face* face);

/**
 * Set the triangulation: `xyz` 3 doubles per vertex, `triangles` 3 indices per triangle, consistently
 * oriented. Validated here (NaN, index range, repeated vertex in a triangle, duplicate triangles,
 * non-manifold edges or vertices, inconsistent orientation, several components): a rejected mesh
 * leaves the face as it was. Zero-area triangles are accepted (see wefm_options.min_beta) and counted.
 */
WEFM_API wefm_status wefm_face_set_mesh(wefm_face* face, int64_t vertex_count, const double* xyz,
                                        int64_t triangle_count, const int32_t* triangles);
WEFM_API wefm_status wefm_face_set_mesh_i64(wefm_face* face, int64_t vertex_count, const double* xyz,
                                            int64_t triangle_count, const int64_t* triangles);
WEFM_API wefm_status wefm_face_set_mesh_from(wefm_face* face, const wefm_mesh* mesh);

WEFM_API wefm_status wefm_face_set_options(wefm_face* face, const wefm_options* options);
WEFM_API wefm_status wefm_face_get_options(const wefm_face* face, wefm_options* options);

/* ---- Topology ------------------------------------------------------------------------------ */
/*
 * Without any call below, the loops are the mesh's boundary cycles, each one edge, and the outer loop
 * is the longest in 3D. A caller with a CAD topology adds edges (chains of vertex indices along facet
 * edges) and loops (ordered edge uses keeping the face on the left). An edge used twice by the loops,
 * once each way, is a repeated edge (seam, slit or scar). A caller with only seams gives facet edges
 * to cut along instead. Topology is validated at the first call that needs it (wefm_face_solve,
 * use queries); errors name the edge or loop.
 */

/** Forget edges, loops, seams and outer-loop choice: back to the derived topology. */
WEFM_API wefm_status wefm_face_clear_topology(wefm_face* face);
/** Add an edge as a chain of `n` vertex indices (n >= 1; n == 1 is a degenerate edge, e.g. a pole). */
WEFM_API wefm_status wefm_face_add_edge(wefm_face* face, int64_t n, const int32_t* chain, int32_t* edge_id);
/** Add a loop of `n` edge uses: edges[j] traversed reversed if reversed[j] != 0 (reversed may be NULL). */
WEFM_API wefm_status wefm_face_add_loop(wefm_face* face, int64_t n, const int32_t* edges,
                                        const int32_t* reversed, int32_t* loop_id);
/** Designate the outer loop: a loop id when loops were given, else a boundary-cycle index. -1 = automatic. */
WEFM_API wefm_status wefm_face_set_outer_loop(wefm_face* face, int32_t loop);
/** Cut along `n` facet edges given as 2n vertex indices (pairs). Each becomes part of a repeated edge. */
WEFM_API wefm_status wefm_face_add_seams(wefm_face* face, int64_t n, const int32_t* vertex_pairs);
/** Force the mode of one edge (wefm_edge_mode). Only repeated edges are affected by the mode. */
WEFM_API wefm_status wefm_face_set_edge_mode(wefm_face* face, int32_t edge, int mode);

/** Build (if needed) and validate the topology and the vertex uses; returns the first problem found. */
WEFM_API wefm_status wefm_face_build(wefm_face* face);
/** Number of edges (given or derived). Builds the topology. */
WEFM_API wefm_status wefm_face_edge_count(wefm_face* face, int64_t* count);
/** Vertex chain of edge `edge`. */
WEFM_API wefm_status wefm_face_get_edge(wefm_face* face, int32_t edge, int32_t* chain, int64_t capacity, int64_t* count);
/** Non-zero in *repeated if the edge is used twice by the loops. */
WEFM_API wefm_status wefm_face_edge_is_repeated(wefm_face* face, int32_t edge, int32_t* repeated);
WEFM_API wefm_status wefm_face_loop_count(wefm_face* face, int64_t* count);
/** Edge uses of a loop: 2 int32 per use (edge id, reversed flag). */
WEFM_API wefm_status wefm_face_get_loop(wefm_face* face, int32_t loop, int32_t* edge_uses, int64_t capacity, int64_t* count);
/** Vertex uses along a loop in order (face on the left). */
WEFM_API wefm_status wefm_face_get_loop_uses(wefm_face* face, int32_t loop, int32_t* uses, int64_t capacity, int64_t* count);
WEFM_API wefm_status wefm_face_outer_loop(wefm_face* face, int32_t* loop);

/* ---- Vertex uses (the unknowns) ------------------------------------------------------------ */

WEFM_API wefm_status wefm_face_use_count(wefm_face* face, int64_t* count);
/** The vertex of every use: 1 int32 per use. */
WEFM_API wefm_status wefm_face_get_use_vertices(wefm_face* face, int32_t* vertices, int64_t capacity, int64_t* count);
/** The uses of every triangle: 3 int32 per triangle, in the triangle's corner order. */
WEFM_API wefm_status wefm_face_get_triangle_uses(wefm_face* face, int32_t* uses, int64_t capacity, int64_t* count);
/** The uses of one vertex (one unless the vertex lies on a repeated edge). */
WEFM_API wefm_status wefm_face_get_vertex_uses(wefm_face* face, int32_t vertex, int32_t* uses, int64_t capacity, int64_t* count);

/* ---- Constraints --------------------------------------------------------------------------- */
/*
 * Caller constraints replace the automatic gauges they make redundant: a constraint whose
 * coefficients do not sum to zero fixes translation; constraints fixing the vector between uses fix
 * rotation and scale. Pins are constraints with one term.
 */

/** Pin use `use` at (u, v). */
WEFM_API wefm_status wefm_face_add_pin(wefm_face* face, int32_t use, double u, double v, int32_t* constraint_id);
/** Add sum_j g_j z_{uses[j]} = c; `coefficients` holds 2n doubles (re, im), `rhs` 2 doubles. */
WEFM_API wefm_status wefm_face_add_constraint(wefm_face* face, int64_t n, const int32_t* uses,
                                              const double* coefficients, const double* rhs, int32_t* constraint_id);
WEFM_API wefm_status wefm_face_clear_constraints(wefm_face* face);

/* ---- Solving ------------------------------------------------------------------------------- */

/**
 * Progress callback: `fraction` in [0,1], `stage` one of "topology", "coefficients", "assembly",
 * "factorise", "solve", "repeated edges", "continuation", "rollout", "quality", "done", "mesh".
 * Return non-zero to cancel. Called on the solving thread.
 */
typedef int (*wefm_progress_fn)(void* user_data, double fraction, const char* stage);
WEFM_API wefm_status wefm_face_set_progress_callback(wefm_face* face, wefm_progress_fn fn, void* user_data);

/** Flatten the face with its options. On failure or cancel the previous result (if any) is kept. */
WEFM_API wefm_status wefm_face_solve(wefm_face* face);
/** Ask a running solve to stop at its next check (thread-safe). The solve returns WEFM_ERROR_CANCELLED. */
WEFM_API wefm_status wefm_face_cancel(wefm_face* face);
/** Non-zero in *solved when a result is available. */
WEFM_API wefm_status wefm_face_has_result(const wefm_face* face, int32_t* solved);

/* ---- Results ------------------------------------------------------------------------------- */

/** UV of every use: 2 doubles per use. */
WEFM_API wefm_status wefm_face_get_uv(wefm_face* face, double* uv, int64_t capacity, int64_t* count);
/** Decision per edge (wefm_edge_mode, AUTO resolved): 1 int32 per edge; non-repeated edges give FREE. */
WEFM_API wefm_status wefm_face_get_edge_modes(wefm_face* face, int32_t* modes, int64_t capacity, int64_t* count);
/** Score of each candidate mode tried for a repeated edge: 5 doubles indexed by wefm_edge_mode (NaN = not tried). */
WEFM_API wefm_status wefm_face_get_edge_scores(wefm_face* face, int32_t edge, double* scores, int64_t capacity, int64_t* count);

typedef struct wefm_report {
  size_t struct_size;
  double score;                  /**< METHOD §8: 1 is perfect; -1 if any flip; -2 if the boundary self-intersects */
  int64_t flipped_triangles;
  int64_t boundary_intersections;
  double area_distortion_mean;   /**< 3D-area weighted mean of |log(UV area / 3D area)| after area normalisation */
  double area_distortion_max;
  double angle_distortion_mean;  /**< 3D-area weighted mean of sigma_max/sigma_min of the Jacobian */
  double angle_distortion_max;
  double uv_area;                /**< total UV area as returned */
  double area_3d;
  double s;                      /**< s of the returned layout: the best-scoring iterate, which may be below the target */
  int32_t converged;             /**< non-zero when every rho fixed point converged */
  int32_t method;
  int32_t s_steps;               /**< continuation steps taken */
  int32_t rho_iterations;        /**< total rho iterations over all steps */
  double rho_change;             /**< final relative rho change */
  int64_t symbolic_analyses;
  int64_t numeric_factorizations;
  int64_t solves;                /**< triangular solve passes with the factor (one per right-hand side) */
  int64_t iterative_iterations;  /**< PCG / roll-out sweep iterations */
  int32_t auto_cut;              /**< non-zero if the solve cut the face itself */
  int32_t degenerate_triangles;  /**< triangles regularised by min_beta */
  double time_topology, time_coefficients, time_assembly, time_analysis, time_factorization,
         time_solve, time_continuation, time_quality, time_total; /**< seconds */
  double peak_memory_mb;         /**< process peak resident set size after the solve (0 if unknown) */
} wefm_report;

/** Zero `report` and set struct_size = `struct_size` (the caller's sizeof); errors as wefm_options_init(). */
WEFM_API wefm_status wefm_report_init(wefm_report* report, size_t struct_size);
WEFM_API wefm_status wefm_face_get_report(const wefm_face* face, wefm_report* report);
/** Per continuation step: 3 doubles (s, rho iterations, final rho change). */
WEFM_API wefm_status wefm_face_get_step_history(const wefm_face* face, double* steps, int64_t capacity, int64_t* count);

/* ---- Mapping ------------------------------------------------------------------------------- */

/**
 * Map `n` UV points (2n doubles) to 3D (3n doubles). `point_status` (n int32, may be NULL) gets
 * WEFM_OK or WEFM_ERROR_OUTSIDE_DOMAIN per point (outside points get the nearest domain point's image).
 * `triangles` (n int32, may be NULL) gets the containing triangle or -1.
 */
WEFM_API wefm_status wefm_face_map_uv_to_3d(wefm_face* face, int64_t n, const double* uv, double* xyz,
                                            int32_t* point_status, int32_t* triangles);
/** Map `n` 3D points (3n doubles) to UV (2n doubles) through the closest point of the triangulation. */
WEFM_API wefm_status wefm_face_map_3d_to_uv(wefm_face* face, int64_t n, const double* xyz, double* uv,
                                            int32_t* point_status, int32_t* triangles);

/* ---- Output -------------------------------------------------------------------------------- */

/** Write OBJ with v (3D), vt (UV per use) and f v/vt. */
WEFM_API wefm_status wefm_face_write_obj(wefm_face* face, const char* path);

/* ============================================================================================= */
/* Meshing the domain (METHOD §9)                                                                */
/* ============================================================================================= */

typedef struct wefm_domain_mesh wefm_domain_mesh;

typedef enum wefm_mesh_type {
  WEFM_MESH_FREE = 0,        /**< constrained Delaunay + refinement, triangles */
  WEFM_MESH_TRANSFINITE = 1  /**< Coons patch on four corners, quads (or split triangles) */
} wefm_mesh_type;

typedef struct wefm_mesh_options {
  size_t struct_size;
  int type;                  /**< wefm_mesh_type. Default FREE */
  double size;               /**< target 3D element size h (> 0). Required */
  int32_t corners[4];        /**< transfinite corners as vertex uses on the outer loop, -1 = detect. Default -1 */
  int quads;                 /**< transfinite: non-zero writes quads, zero splits each into two triangles. Default 1 */
  int smoothing_iterations;  /**< free meshes: UV smoothing passes accepted only if 3D quality improves. Default 5 */
  double corner_angle_deg;   /**< loop vertices turning more than this are kept as nodes. Default 30 */
  double min_angle_deg;      /**< Delaunay refinement angle bound in UV. Default 28 */
  int64_t max_elements;      /**< refuse to exceed this many elements (0 = no cap). Default 0 */
} wefm_mesh_options;

typedef struct wefm_mesh_report {
  size_t struct_size;
  int64_t nodes, elements;
  int32_t nodes_per_element;     /**< 3 or 4 */
  double lambda_mesh;            /**< geometric mean of Lo's quality on the 3D triangles */
  double lambda_min;
  double fraction_below_0_6;     /**< share of triangles with lambda < 0.6 */
  double scaled_jacobian_min;    /**< quads only, else 0 */
  double scaled_jacobian_mean;
  double wiggle_max;             /**< transfinite only: eq. 12 over rail lines, else 0 */
  double wiggle_mean;
  double time_boundary, time_mesh, time_smooth, time_map;
} wefm_mesh_report;

/** Fill `options` with the defaults (size must still be set); `struct_size` as for wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_options_init(wefm_mesh_options* options, size_t struct_size);
/** Zero `report` and set struct_size = `struct_size`; errors as wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_report_init(wefm_mesh_report* report, size_t struct_size);

/**
 * Use caller-given 3D nodes along edge `edge` (3n doubles, in the edge's direction, including both end
 * vertices) instead of discretising it at the global size. The nodes must lie on the edge's facet chain.
 */
WEFM_API wefm_status wefm_face_set_edge_nodes(wefm_face* face, int32_t edge, int64_t n, const double* xyz);
WEFM_API wefm_status wefm_face_clear_edge_nodes(wefm_face* face);

/** Mesh the solved domain and map it to 3D. Needs a result (wefm_face_solve). */
WEFM_API wefm_status wefm_face_mesh_domain(wefm_face* face, const wefm_mesh_options* options, wefm_domain_mesh** out);
WEFM_API wefm_status wefm_domain_mesh_retain(wefm_domain_mesh* mesh);
WEFM_API void wefm_domain_mesh_release(wefm_domain_mesh* mesh);
/** Node UV: 2 doubles per node. */
WEFM_API wefm_status wefm_domain_mesh_get_uv(const wefm_domain_mesh* mesh, double* uv, int64_t capacity, int64_t* count);
/** Node 3D positions: 3 doubles per node. */
WEFM_API wefm_status wefm_domain_mesh_get_xyz(const wefm_domain_mesh* mesh, double* xyz, int64_t capacity, int64_t* count);
/** Elements: nodes_per_element int32 per element. */
WEFM_API wefm_status wefm_domain_mesh_get_elements(const wefm_domain_mesh* mesh, int32_t* nodes, int64_t capacity, int64_t* count);
WEFM_API wefm_status wefm_domain_mesh_get_report(const wefm_domain_mesh* mesh, wefm_mesh_report* report);
/** Write the 3D mesh as OBJ (with vt = UV). */
WEFM_API wefm_status wefm_domain_mesh_write_obj(const wefm_domain_mesh* mesh, const char* path);

#ifdef __cplusplus
}

/* C++ callers may leave out the size: these pass sizeof as the caller's compiler sees it (see "ABI"
 * above). They are inline in the caller, so they add no symbols to the library. */
inline wefm_status wefm_options_init(wefm_options* options) { return wefm_options_init(options, sizeof(wefm_options)); }
inline wefm_status wefm_mesh_info_init(wefm_mesh_info* info) { return wefm_mesh_info_init(info, sizeof(wefm_mesh_info)); }
inline wefm_status wefm_report_init(wefm_report* report) { return wefm_report_init(report, sizeof(wefm_report)); }
inline wefm_status wefm_mesh_options_init(wefm_mesh_options* options) { return wefm_mesh_options_init(options, sizeof(wefm_mesh_options)); }
inline wefm_status wefm_mesh_report_init(wefm_mesh_report* report) { return wefm_mesh_report_init(report, sizeof(wefm_mesh_report)); }
#endif

#endif /* WEFM_WEFM_H */
