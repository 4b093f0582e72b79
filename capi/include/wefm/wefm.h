/**
 * @file wefm.h
 * @brief The stable C API of wefm, the Weighted Edge Flattening Method library.
 *
 * wefm flattens a 3D triangulated surface (a "facetted face") into a low-distortion 2D domain,
 * meshes that domain and maps the mesh back to 3D. Link libwefm (CMake: find_package(wefm),
 * target wefm::wefm; pkg-config: wefm). The API reference is built from this file (docs/Doxyfile).
 * The Python and Fortran declarations are generated from it: after changing a declaration, run
 * `python3 scripts/gen_bindings.py` (ctest bindings.generated_current fails until the output is current).
 *
 * The function comments below name only the errors particular to each function; the ones every
 * function shares (NULL arguments, buffer sizes, exhausted memory) are in the conventions.
 *
 * @verbatim
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
 *              be used from two threads at once, with two exceptions: wefm_face_cancel() may be called
 *              from any thread while wefm_face_solve()/wefm_face_mesh_domain() runs on another; and
 *              a wefm_mesh, which nothing changes once created, may be read by any number of
 *              threads at once (wefm_mesh_get_*, wefm_face_set_mesh_from, retain and release).
 *              With wefm_options.threads <= 1 the library starts no threads of its own; with more,
 *              a solve runs its coefficients, assembly, sparse factorisations (two groups of
 *              subtrees of the elimination tree at once), continuation passes (linearisation,
 *              energy, products) and the preconditioner's triangular solves on that many
 *              short-lived threads (joined before it returns); on faces of 20,000 vertex uses and
 *              more the global method's symbolic analysis takes one of them, beside the
 *              coefficients and assembly on the others. Work is cut into pieces fixed by the face
 *              alone and every sum runs in a fixed order, so layouts are bit-identical for any
 *              thread count. The BLAS calls run on the calling threads, and OpenBLAS's own pool
 *              stays as the host set it (openblas_set_num_threads, OPENBLAS_NUM_THREADS): OpenBLAS
 *              splits a call by its own thread count and the call's sizes, which do not depend on
 *              wefm's, so the layouts stay bit-identical for any wefm thread count under any one
 *              OpenBLAS setting (another OpenBLAS thread count moves their last bits). A host may
 *              have every solve set the pool instead (WEFM_PROCESS_BLAS_THREADS; the wefm tool
 *              sets 1). Where CHOLMOD still factorises, its OpenMP loops run on the solving
 *              thread alone: that thread's OpenMP max-active-levels is 0 during the factorisation
 *              and restored after (a per-thread setting in OpenMP 5 and libgomp; no other thread
 *              sees it). Measured times by thread count: docs/PERFORMANCE.md.
 * Process.     No function changes what belongs to the whole process: OpenBLAS's threads, OpenMP's
 *              settings, SuiteSparse's global configuration (SuiteSparse_config), the allocator,
 *              signal handlers, the locale, the environment, the floating-point environment or
 *              resource limits stay as the host set them, and no memory the library does not
 *              hold is advised. Two of them speed a large solve up; a host opts in with
 *              wefm_set_process_policy() (WEFM_PROCESS_BLAS_THREADS, WEFM_PROCESS_HUGE_PAGES),
 *              as the wefm tool does for itself. What the default gives up (a 1M-triangle face at
 *              s = 0 and 1): docs/PERFORMANCE.md, "Process policy".
 * Memory.      With WEFM_PROCESS_HUGE_PAGES on, a solve advises its large arrays (4 MB and up) for
 *              transparent huge pages (madvise MADV_HUGEPAGE, while the system's free memory is
 *              ample): otherwise the first touch of every 4 KB page is a page fault, which is
 *              costly on a virtual machine; in CHOLMOD builds SuiteSparse's malloc and calloc go
 *              through wrappers that add that advice. Off by default: the advice outlives the
 *              block on its address range, which the host's allocator reuses. What the library
 *              cannot advise (smaller blocks, Eigen's arrays) a host on glibc >= 2.35 reaches by
 *              starting with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 in its environment, as the
 *              wefm tool does (apps/README.md, "Environment"). The library reads one environment
 *              variable, WEFM_FLOAT_FACTOR (=0 keeps the preconditioner in double precision, for
 *              diagnosis; docs/SOLVER.md), once.
 * Re-entrancy. A progress callback may call back into the face that is solving or meshing, but only
 *              to read it or stop it: wefm_face_cancel, wefm_face_retain, wefm_face_release, wefm_face_last_error,
 *              wefm_face_has_result, wefm_face_get_options, the topology queries (*_count, get_edge,
 *              get_loop, get_*_uses, ...) and the queries of the previous result (get_uv, get_report,
 *              get_edge_modes, get_edge_scores, get_step_history, map_*, write_obj). Every call that
 *              would change the face (set_*, add_*, clear_*, build, solve, mesh_domain, set_edge_nodes,
 *              set_progress_callback) returns WEFM_ERROR_INVALID_STATE until wefm_face_solve (or
 *              wefm_face_mesh_domain) returns. A release of the last reference from the callback does
 *              not free the face under its solve: the call frees it as it returns (the caller must not
 *              use it after).
 * Exceptions.  None cross this boundary. Memory exhaustion (also a thread that cannot be started for
 *              want of memory or thread slots) returns WEFM_ERROR_OUT_OF_MEMORY.
 * Invalidation. Setting a new mesh clears topology, constraints and results. Changing topology
 *              clears constraints (use ids change with it) and results. Changing constraints or
 *              edge modes clears results. Options apply to the next solve: the result stays
 *              (except auto_cut on a face it cuts: that changes the topology). A failed or
 *              cancelled solve keeps the previous result.
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
 *              Every function declared here keeps its ABI across minor versions; there is no
 *              experimental section yet. The exported
 *              symbols and the ABI are pinned by capi/abi/ and checked by ctest.
 * @endverbatim
 */
#ifndef WEFM_WEFM_H
#define WEFM_WEFM_H

#include <stddef.h>
#include <stdint.h>

/** Version of this header; compare with wefm_version() / wefm_version_number() at run time. The
 *  SONAME is libwefm.so.WEFM_VERSION_MAJOR. */
#define WEFM_VERSION_MAJOR 0
#define WEFM_VERSION_MINOR 1 /**< see WEFM_VERSION_MAJOR */
#define WEFM_VERSION_PATCH 0 /**< see WEFM_VERSION_MAJOR */
/** MAJOR * 10000 + MINOR * 100 + PATCH. */
#define WEFM_VERSION_NUMBER (WEFM_VERSION_MAJOR * 10000 + WEFM_VERSION_MINOR * 100 + WEFM_VERSION_PATCH)

/** Marks the exported functions (default visibility; the library is built with hidden visibility). */
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

/** What every fallible function returns; WEFM_OK is 0. Names: wefm_status_string(). */
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

/**
 * Name of a status code.
 * @param status  any value, also ones not in wefm_status.
 * @return "WEFM_OK", "WEFM_ERROR_NULL_ARGUMENT", ...: a static string, never NULL; unknown codes give
 *         "WEFM_ERROR_UNKNOWN". Never fails.
 */
WEFM_API const char* wefm_status_string(wefm_status status);

/**
 * Message of the last failure on this thread that had no handle to carry it: creation, NULL handles,
 * file reading, *_init, wefm_mesh_* calls.
 * @return "" if none. Owned by the library, valid until the next failing call on this thread.
 */
WEFM_API const char* wefm_last_error(void);

/* ============================================================================================= */
/* Version                                                                                       */
/* ============================================================================================= */

/** Run-time version as "MAJOR.MINOR.PATCH" (static string). Compare with WEFM_VERSION_* to detect a
 *  header/library mismatch. Never fails. */
WEFM_API const char* wefm_version(void);
/** Run-time version as WEFM_VERSION_NUMBER (MAJOR*10000 + MINOR*100 + PATCH). Never fails. */
WEFM_API int wefm_version_number(void);
/** Non-zero if this build factorises with SuiteSparse CHOLMOD, zero for the Eigen-only build (where
 *  WEFM_SOLVER_CHOLMOD gives WEFM_ERROR_UNSUPPORTED). Never fails. */
WEFM_API int wefm_has_suitesparse(void);

/* ============================================================================================= */
/* Process policy                                                                                */
/* ============================================================================================= */

/** Keys of wefm_set_process_policy(): settings of the whole process that the library changes only
 *  when the host asks ("Process." at the top). Every key is 0, hands off, until it is set. */
typedef enum wefm_process_policy {
  /** OpenBLAS's thread count. 0 (the default): the library never sets it; the pool stays as the
   *  host set it. n >= 1: every solve (wefm_face_solve) sets OpenBLAS's pool to n threads,
   *  process-wide, and leaves it so; the wefm tool sets 1. 1 spares a solve the pool threads'
   *  spin-waits between its many small BLAS calls. WEFM_ERROR_UNSUPPORTED for n >= 1 where the
   *  process has no OpenBLAS. */
  WEFM_PROCESS_BLAS_THREADS = 1,
  /** Transparent huge pages. 0 (the default): no advice, SuiteSparse_config untouched. 1: the
   *  library advises its large arrays for huge pages ("Memory." at the top) and, in CHOLMOD builds,
   *  points SuiteSparse_config.malloc_func and calloc_func at wrappers that add that advice where
   *  they hold the C library's malloc and calloc (a host's own allocator there is kept; blocks stay
   *  ordinary malloc blocks, freed by free()). Setting 0 again stops the advice and puts malloc and
   *  calloc back where the wrappers still are. Set it while no SuiteSparse call runs in the
   *  process (SuiteSparse_config is a plain global). */
  WEFM_PROCESS_HUGE_PAGES = 2
} wefm_process_policy;

/**
 * Sets a process policy: the host's explicit permission for the library to change a setting of the
 * whole process. Applies to the solves that start after the call.
 * @param key    a wefm_process_policy.
 * @param value  see the key; 0 is always hands off.
 * @return WEFM_ERROR_INVALID_ARGUMENT for an unknown key or a value out of the key's range
 *         (BLAS threads 0 .. 1024, huge pages 0 or 1); WEFM_ERROR_UNSUPPORTED as the key says.
 *         On failure nothing changes and wefm_last_error() names the key and value.
 */
WEFM_API wefm_status wefm_set_process_policy(wefm_process_policy key, int64_t value);

/**
 * The value a process policy holds (0 until wefm_set_process_policy() set it).
 * @return WEFM_ERROR_INVALID_ARGUMENT for an unknown key.
 */
WEFM_API wefm_status wefm_get_process_policy(wefm_process_policy key, int64_t* value);

/* ============================================================================================= */
/* Options                                                                                       */
/* ============================================================================================= */

/** wefm_options.method: how the layout is computed. */
typedef enum wefm_method {
  WEFM_METHOD_GLOBAL = 0,  /**< global least squares with Lagrange constraints (paper §4.2) */
  WEFM_METHOD_ROLLOUT = 1  /**< iterative roll-out with Gauss-Seidel sweeps (paper §4.1) */
} wefm_method;

/** wefm_options.residual: how the surface term sums the prediction errors (METHOD §5). */
typedef enum wefm_residual {
  WEFM_RESIDUAL_PER_HALF_EDGE = 0, /**< each half-edge's prediction error squared (default): every
                                        triangle's shape is fitted; one-ring sparsity */
  WEFM_RESIDUAL_PER_USE = 1        /**< eq. 7 as printed: one residual per use, the weighted sum of its
                                        predictions' errors, which can cancel each other */
} wefm_residual;

/** How the two sides of a repeated edge (seam, slit, scar) are related in the domain. */
typedef enum wefm_edge_mode {
  WEFM_EDGE_AUTO = 0,      /**< choose by score (METHOD §7 step 2) */
  WEFM_EDGE_FREE = 1,      /**< the two sides are independent */
  WEFM_EDGE_PERIODIC = 2,  /**< the two sides are translates of each other */
  WEFM_EDGE_SCAR = 3,      /**< the two sides coincide (at one point each: forced on a cylinder's
                                seam this gives the uncut annulus with the seam as an interior line) */
  WEFM_EDGE_ROTATIONAL = 4 /**< the two sides are related by a rotation about a free centre */
} wefm_edge_mode;

/** wefm_options.solver: the sparse factorisation. */
typedef enum wefm_solver {
  WEFM_SOLVER_AUTO = 0,    /**< CHOLMOD when built with it, else Eigen */
  WEFM_SOLVER_CHOLMOD = 1, /**< SuiteSparse CHOLMOD supernodal Cholesky */
  WEFM_SOLVER_EIGEN = 2    /**< Eigen's SimplicialLDLT (permissive licence) */
} wefm_solver;

/** Solver options; fill with wefm_options_init() first (see "ABI" in the conventions). */
typedef struct wefm_options {
  size_t struct_size;        /**< set by wefm_options_init */
  double s;                  /**< target roll-out exponent in [0,2]: 0 conformal, 1 altitude, 2 area. Default 1 */
  double k;                  /**< weight normalisation exponent, 1 or 0.5 (any value in [0,1]). Default 0.5 */
  double boundary_weight;    /**< mu, dimensionless weight of the boundary term (>= 0). Default 1 */
  int curvature_adjust;      /**< non-zero: scale beta by Theta/2pi at interior uses. Default 1 */
  int method;                /**< wefm_method. Default WEFM_METHOD_GLOBAL */
  int solver;                /**< wefm_solver. Default WEFM_SOLVER_AUTO */
  int default_edge_mode;     /**< wefm_edge_mode for repeated edges not set per edge. Default AUTO */
  double s_step;             /**< largest continuation step in s (0.001 <= s_step <= 2). A step up by more
                                  than 1 is tentative: where Gauss-Newton cuts one of its steps short, it is
                                  taken again in steps of 1 (wefm_report.abandoned_steps). Default 2 */
  double rho_tolerance;      /**< the last continuation step ends when max relative rho change < this (steps below the target s at 10x this). Default 1e-3 */
  int max_rho_iterations;    /**< Gauss-Newton iterations per s step; reaching it reports non-convergence. Default 50 */
  double rollout_tolerance;  /**< roll-out sweep stop: max move / mean edge < this. Default 1e-10 */
  int max_rollout_sweeps;    /**< Default 10000 */
  double score_threshold;    /**< return after the conformal solve if its score >= this. Default 2 (never) */
  int auto_cut;              /**< non-zero: cut annuli and closed genus-0 surfaces without caller seams or
                                  loops automatically (docs/SOLVER.md). Toggling it on a face it cuts is a
                                  topology change. Default 0 */
  int threads;               /**< threads of a solve's own loops and preconditioner solves (0 = 1); the layout is
                                  the same for any count (see Threads). Default 0 */
  double memory_limit_mb;    /**< refuse solves estimated above this many MB with WEFM_ERROR_OUT_OF_MEMORY,
                                  before the factor is allocated (0 = no limit). The estimate: the
                                  factor's values as the symbolic analysis sizes them, plus 0.75 KB
                                  per triangle for the rest (within -8% .. +16% of the measured peak
                                  of 1M-triangle solves at s = 0, 1, 2). Default 0 */
  double min_beta;           /**< altitude/base floor for degenerate triangles (> 0). Default 1e-3 */
  int residual;              /**< wefm_residual. Default WEFM_RESIDUAL_PER_HALF_EDGE */
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

/** A triangle mesh read from a file or made from arrays (opaque, reference counted). */
typedef struct wefm_mesh wefm_mesh;

/** What wefm_mesh_get_info() reports; fill with wefm_mesh_info_init() first. */
typedef struct wefm_mesh_info {
  size_t struct_size;            /**< set by wefm_mesh_info_init() */
  int64_t vertices, triangles;   /**< counts */
  int64_t boundary_loops;        /**< boundary cycles of the triangulation */
  int64_t components;            /**< edge-connected components */
  int64_t genus;                 /**< from Euler characteristic, per the whole mesh; -1 if non-manifold */
  int64_t non_manifold_edges;    /**< edges with more than two triangles */
  int64_t non_manifold_vertices; /**< vertices whose triangle fan is not one disk or half-disk */
  int64_t degenerate_triangles;  /**< zero-area triangles (collinear or repeated vertices) */
  int64_t duplicate_triangles;   /**< triangles on the same three vertices as another */
  int64_t inconsistent_edges;    /**< interior edges whose two triangles disagree in orientation */
  int64_t merged_vertices;       /**< vertices merged while reading (STL) */
  double bbox_min[3], bbox_max[3]; /**< axis-aligned bounding box */
  double area;                   /**< total 3D area */
  double mean_edge_length;       /**< mean length of the facet edges */
} wefm_mesh_info;

/** Zero `info` and set struct_size = `struct_size` (the caller's sizeof); errors as wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_info_init(wefm_mesh_info* info, size_t struct_size);

/**
 * Read a triangle mesh: OBJ, OFF, STL (ASCII or binary) or PLY, chosen by extension.
 * STL vertices closer than `merge_tolerance` (relative to the bounding-box diagonal; <= 0 uses 1e-9)
 * are merged; the count is in wefm_mesh_info.merged_vertices. Polygons are fan-triangulated.
 * @param path             file name (UTF-8 bytes as the C library opens them).
 * @param merge_tolerance  STL vertex merging distance, relative; <= 0 for the default.
 * @param[out] out         the new mesh, one reference owned by the caller (wefm_mesh_release());
 *                         NULL on failure.
 * @return WEFM_ERROR_IO (cannot open or read), WEFM_ERROR_UNSUPPORTED (extension), WEFM_ERROR_INVALID_MESH
 *         (malformed content); wefm_last_error() says what is wrong.
 */
WEFM_API wefm_status wefm_mesh_read(const char* path, double merge_tolerance, wefm_mesh** out);
/**
 * Create a mesh from arrays (copied). Indices are checked for range only.
 * @param vertex_count    number of vertices (0 .. 2^31-1).
 * @param xyz             3 doubles per vertex.
 * @param triangle_count  number of triangles.
 * @param triangles       3 vertex indices per triangle.
 * @param[out] out        the new mesh, owned by the caller (wefm_mesh_release()); NULL on failure.
 * @return WEFM_ERROR_INVALID_ARGUMENT (negative or too large counts), WEFM_ERROR_OUT_OF_RANGE (an index);
 *         details in wefm_last_error().
 */
WEFM_API wefm_status wefm_mesh_create(int64_t vertex_count, const double* xyz, int64_t triangle_count,
                                      const int32_t* triangles, wefm_mesh** out);
/** Add a reference to `mesh` (each needs its own wefm_mesh_release()). */
WEFM_API wefm_status wefm_mesh_retain(wefm_mesh* mesh);
/** Drop a reference; the last one frees the mesh. NULL is ignored. Faces made from it keep their copy. */
WEFM_API void wefm_mesh_release(wefm_mesh* mesh);
/**
 * The vertices, by the size-query protocol (see "Buffers").
 * @param mesh          the mesh.
 * @param[out] xyz      3 doubles per vertex, or NULL to query the size.
 * @param capacity      elements (doubles) available in `xyz`.
 * @param[out] count    elements needed: 3 * vertices.
 * @return WEFM_ERROR_BUFFER_TOO_SMALL if capacity < *count (nothing written).
 */
WEFM_API wefm_status wefm_mesh_get_vertices(const wefm_mesh* mesh, double* xyz, int64_t capacity, int64_t* count);
/** The triangles, 3 int32 vertex indices each, by the size-query protocol (as wefm_mesh_get_vertices()). */
WEFM_API wefm_status wefm_mesh_get_triangles(const wefm_mesh* mesh, int32_t* tri, int64_t capacity, int64_t* count);
/**
 * What a user checks before flattening: counts, boundary loops, genus, non-manifold and degenerate
 * elements, bounding box, area.
 * @param mesh       the mesh.
 * @param[in,out] info  filled with wefm_mesh_info_init() first; only its first struct_size bytes are written.
 * @return WEFM_ERROR_INVALID_ARGUMENT if info->struct_size is too small (init not called).
 */
WEFM_API wefm_status wefm_mesh_get_info(const wefm_mesh* mesh, wefm_mesh_info* info);

/* ============================================================================================= */
/* Faces                                                                                         */
/* ============================================================================================= */

/** A face to flatten: mesh, topology, constraints, options and the last result (opaque, reference counted). */
typedef struct wefm_face wefm_face;

/**
 * Create an empty face (no mesh yet: solve and queries give WEFM_ERROR_INVALID_STATE until
 * wefm_face_set_mesh()).
 * @param[out] out  the new face, one reference owned by the caller (wefm_face_release()); NULL on failure.
 * @return WEFM_ERROR_OUT_OF_MEMORY.
 */
WEFM_API wefm_status wefm_face_create(wefm_face** out);
/** Add a reference to `face` (each needs its own wefm_face_release()). Thread-safe. */
WEFM_API wefm_status wefm_face_retain(wefm_face* face);
/** Drop a reference; the last one frees the face and its results. NULL is ignored. Thread-safe. */
WEFM_API void wefm_face_release(wefm_face* face);
/** Detailed message of the last failing call on this face ("" if none): owned by the face, valid until
 *  the next call on it. A NULL face gives a static message, never NULL. */
WEFM_API const char* wefm_face_last_error(const wefm_face* face);

/**
 * Set the triangulation: `xyz` 3 doubles per vertex, `triangles` 3 indices per triangle, consistently
 * oriented. Validated here (NaN, index range, repeated vertex in a triangle, duplicate triangles,
 * non-manifold edges or vertices, inconsistent orientation, several components): a rejected mesh
 * leaves the face as it was. Zero-area triangles are accepted (see wefm_options.min_beta) and counted.
 * The arrays are copied. A new mesh clears topology, constraints and results.
 * @param face            the face.
 * @param vertex_count    number of vertices (< 2^31).
 * @param xyz             3 doubles per vertex.
 * @param triangle_count  number of triangles.
 * @param triangles       3 int32 vertex indices per triangle.
 * @return WEFM_ERROR_INVALID_ARGUMENT (negative counts), WEFM_ERROR_INVALID_MESH (what is wrong and
 *         where: wefm_face_last_error()).
 */
WEFM_API wefm_status wefm_face_set_mesh(wefm_face* face, int64_t vertex_count, const double* xyz,
                                        int64_t triangle_count, const int32_t* triangles);
/** wefm_face_set_mesh() with int64_t triangle indices (values must still fit in int32_t). */
WEFM_API wefm_status wefm_face_set_mesh_i64(wefm_face* face, int64_t vertex_count, const double* xyz,
                                            int64_t triangle_count, const int64_t* triangles);
/** wefm_face_set_mesh() from a wefm_mesh (copied: the mesh may be released afterwards). */
WEFM_API wefm_status wefm_face_set_mesh_from(wefm_face* face, const wefm_mesh* mesh);

/**
 * Set the options of the next solves (the face starts with the defaults of wefm_options_init()).
 * @param face     the face.
 * @param options  filled with wefm_options_init() first; read up to options->struct_size bytes, fields
 *                 past it take their defaults. Copied.
 * @return WEFM_ERROR_INVALID_ARGUMENT (struct_size too small, a value out of its range: the message
 *         names the field), WEFM_ERROR_UNSUPPORTED (WEFM_SOLVER_CHOLMOD in a build without it). On error
 *         the face keeps its previous options.
 */
WEFM_API wefm_status wefm_face_set_options(wefm_face* face, const wefm_options* options);
/**
 * The face's current options.
 * @param face             the face.
 * @param[in,out] options  struct_size set (wefm_options_init()); only that many bytes are written.
 * @return WEFM_ERROR_INVALID_ARGUMENT if options->struct_size is too small.
 */
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

/** Forget edges, loops, seams, edge modes and the outer-loop choice: back to the derived topology.
 *  Like every topology change, clears constraints and the result. */
WEFM_API wefm_status wefm_face_clear_topology(wefm_face* face);
/**
 * Add an edge as a chain of vertex indices along facet edges.
 * @param face          the face (with a mesh).
 * @param n             chain length (n >= 1; n == 1 is a degenerate edge, e.g. a pole).
 * @param chain         n vertex indices (copied).
 * @param[out] edge_id  the new edge's id (0, 1, ... in order of addition); may be NULL.
 * @return WEFM_ERROR_INVALID_ARGUMENT (n < 1), WEFM_ERROR_OUT_OF_RANGE (a vertex index),
 *         WEFM_ERROR_INVALID_STATE (no mesh). Chains that are not along facet edges are reported by
 *         wefm_face_build() as WEFM_ERROR_INVALID_TOPOLOGY.
 */
WEFM_API wefm_status wefm_face_add_edge(wefm_face* face, int64_t n, const int32_t* chain, int32_t* edge_id);
/**
 * Add a loop of edge uses keeping the face on the left.
 * @param face          the face.
 * @param n             number of edge uses (>= 1).
 * @param edges         n edge ids from wefm_face_add_edge().
 * @param reversed      n flags: edges[j] is traversed against its chain if reversed[j] != 0; NULL = none.
 * @param[out] loop_id  the new loop's id; may be NULL.
 * @return WEFM_ERROR_INVALID_ARGUMENT (n < 1), WEFM_ERROR_OUT_OF_RANGE (an edge id not added yet).
 *         Loops that do not close are reported by wefm_face_build().
 */
WEFM_API wefm_status wefm_face_add_loop(wefm_face* face, int64_t n, const int32_t* edges,
                                        const int32_t* reversed, int32_t* loop_id);
/** Designate the outer loop: a loop id when loops were given, else a boundary-cycle index; -1 = automatic
 *  (the longest in 3D). WEFM_ERROR_OUT_OF_RANGE below -1; a loop that does not exist is reported by
 *  wefm_face_build() as WEFM_ERROR_INVALID_TOPOLOGY. */
WEFM_API wefm_status wefm_face_set_outer_loop(wefm_face* face, int32_t loop);
/**
 * Cut along facet edges; each becomes part of a repeated edge (seam).
 * @param face          the face.
 * @param n             number of facet edges (>= 0).
 * @param vertex_pairs  2n vertex indices, one pair per facet edge (copied).
 * @return WEFM_ERROR_INVALID_ARGUMENT (n < 0), WEFM_ERROR_OUT_OF_RANGE (a vertex index). Pairs that are
 *         not facet edges are reported by wefm_face_build().
 */
WEFM_API wefm_status wefm_face_add_seams(wefm_face* face, int64_t n, const int32_t* vertex_pairs);
/**
 * Force the mode of one edge (only repeated edges are affected by the mode).
 * @param face  the face.
 * @param edge  edge id (0 .. wefm_face_edge_count() - 1).
 * @param mode  a wefm_edge_mode; WEFM_EDGE_AUTO lets the solve choose by score.
 * @return WEFM_ERROR_OUT_OF_RANGE (edge), WEFM_ERROR_INVALID_ARGUMENT (mode), WEFM_ERROR_INVALID_STATE
 *         (no mesh); topology errors as wefm_face_build(). Clears the result.
 */
WEFM_API wefm_status wefm_face_set_edge_mode(wefm_face* face, int32_t edge, int mode);

/** Build (if needed) and validate the topology and the vertex uses.
 *  @return the first problem found: WEFM_ERROR_INVALID_STATE (no mesh), WEFM_ERROR_INVALID_TOPOLOGY
 *          (the message names the edge or loop). */
WEFM_API wefm_status wefm_face_build(wefm_face* face);
/** Number of edges (given or derived) in *count. Builds the topology: errors as wefm_face_build(). */
WEFM_API wefm_status wefm_face_edge_count(wefm_face* face, int64_t* count);
/** Vertex chain of edge `edge` (1 int32 per vertex), by the size-query protocol.
 *  WEFM_ERROR_OUT_OF_RANGE for an edge that does not exist; topology errors as wefm_face_build(). */
WEFM_API wefm_status wefm_face_get_edge(wefm_face* face, int32_t edge, int32_t* chain, int64_t capacity, int64_t* count);
/** Non-zero in *repeated if the edge is used twice by the loops. WEFM_ERROR_OUT_OF_RANGE for a bad edge. */
WEFM_API wefm_status wefm_face_edge_is_repeated(wefm_face* face, int32_t edge, int32_t* repeated);
/** Number of loops (given, or the boundary cycles) in *count. Errors as wefm_face_build(). */
WEFM_API wefm_status wefm_face_loop_count(wefm_face* face, int64_t* count);
/** Edge uses of a loop: 2 int32 per use (edge id, reversed flag), by the size-query protocol.
 *  WEFM_ERROR_OUT_OF_RANGE for a loop that does not exist. */
WEFM_API wefm_status wefm_face_get_loop(wefm_face* face, int32_t loop, int32_t* edge_uses, int64_t capacity, int64_t* count);
/** Vertex uses along a loop in order (face on the left), by the size-query protocol.
 *  WEFM_ERROR_OUT_OF_RANGE for a loop that does not exist. */
WEFM_API wefm_status wefm_face_get_loop_uses(wefm_face* face, int32_t loop, int32_t* uses, int64_t capacity, int64_t* count);
/** The outer loop's id in *loop (given or chosen). Errors as wefm_face_build(). */
WEFM_API wefm_status wefm_face_outer_loop(wefm_face* face, int32_t* loop);

/* ---- Vertex uses (the unknowns) ------------------------------------------------------------ */

/** Number of vertex uses (the unknowns: a vertex on a repeated edge has one use per side) in *count.
 *  Errors as wefm_face_build(). */
WEFM_API wefm_status wefm_face_use_count(wefm_face* face, int64_t* count);
/** The vertex of every use: 1 int32 per use, by the size-query protocol. */
WEFM_API wefm_status wefm_face_get_use_vertices(wefm_face* face, int32_t* vertices, int64_t capacity, int64_t* count);
/** The uses of every triangle: 3 int32 per triangle, in the triangle's corner order (size-query protocol). */
WEFM_API wefm_status wefm_face_get_triangle_uses(wefm_face* face, int32_t* uses, int64_t capacity, int64_t* count);
/** The uses of one vertex (one unless the vertex lies on a repeated edge), by the size-query protocol.
 *  WEFM_ERROR_OUT_OF_RANGE for a vertex index outside the mesh. */
WEFM_API wefm_status wefm_face_get_vertex_uses(wefm_face* face, int32_t vertex, int32_t* uses, int64_t capacity, int64_t* count);

/* ---- Constraints --------------------------------------------------------------------------- */
/*
 * Caller constraints replace the automatic gauges they make redundant: a constraint whose
 * coefficients do not sum to zero fixes translation; constraints fixing the vector between uses fix
 * rotation and scale. Pins are constraints with one term.
 *
 * Range: a constraint's |c| over its largest |g_j| (per real and imaginary part) may be at most
 * 1e10 mean facet-edge lengths of the mesh. Farther out, double rounding of a position exceeds 1e-6
 * of an edge (and near DBL_MAX the layout overflows): the solve returns
 * WEFM_ERROR_INVALID_CONSTRAINT naming the constraint. Rows are scaled by their largest coefficient
 * before the solve, so coefficients as small as 1e-300 are fine. All-zero coefficients with c != 0
 * are WEFM_ERROR_INVALID_CONSTRAINT at the solve too.
 */

/**
 * Pin use `use` at (u, v): a constraint with one term. Clears the result.
 * @param face                the face.
 * @param use                 a vertex use (wefm_face_get_vertex_uses()).
 * @param u                   target u.
 * @param v                   target v.
 * @param[out] constraint_id  the constraint's id; may be NULL.
 * @return WEFM_ERROR_INVALID_CONSTRAINT for an unknown use or a non-finite u or v (here or at the
 *         solve), and at the solve for a pin out of range (see "Range" above).
 */
WEFM_API wefm_status wefm_face_add_pin(wefm_face* face, int32_t use, double u, double v, int32_t* constraint_id);
/**
 * Add the linear constraint sum_j g_j z_{uses[j]} = c. Clears the result.
 * @param face                the face.
 * @param n                   number of terms (>= 1).
 * @param uses                n vertex uses.
 * @param coefficients        2n doubles: g_j as (re, im).
 * @param rhs                 2 doubles: c as (re, im).
 * @param[out] constraint_id  the constraint's id; may be NULL.
 * @return WEFM_ERROR_INVALID_CONSTRAINT (n < 1, an unknown use, a non-finite value; at the solve, a
 *         constraint out of range, see "Range" above); WEFM_ERROR_SINGULAR at the solve for
 *         contradictory constraints.
 */
WEFM_API wefm_status wefm_face_add_constraint(wefm_face* face, int64_t n, const int32_t* uses,
                                              const double* coefficients, const double* rhs, int32_t* constraint_id);
/** Remove every caller constraint (pins too): back to the automatic gauges. Clears the result. */
WEFM_API wefm_status wefm_face_clear_constraints(wefm_face* face);

/* ---- Solving ------------------------------------------------------------------------------- */

/**
 * Progress callback: `fraction` in [0,1], `stage` one of "topology", "coefficients", "assembly",
 * "factorise", "solve", "repeated edges", "continuation", "rollout", "quality", "done"; and "mesh"
 * from wefm_face_mesh_domain().
 * Return non-zero to cancel. Called on the solving thread. It may only read or cancel the face it
 * reports on (see "Re-entrancy" in the conventions): changes return WEFM_ERROR_INVALID_STATE.
 */
typedef int (*wefm_progress_fn)(void* user_data, double fraction, const char* stage);
/** Set (or with fn = NULL remove) the progress callback of later solves; `user_data` is passed back
 *  unchanged and never dereferenced by the library. */
WEFM_API wefm_status wefm_face_set_progress_callback(wefm_face* face, wefm_progress_fn fn, void* user_data);

/**
 * Flatten the face with its options, topology and constraints. On failure or cancel the previous
 * result (if any) is kept; WEFM_ERROR_NOT_CONVERGED keeps the best layout reached as the result.
 * @return WEFM_ERROR_INVALID_STATE (no mesh), WEFM_ERROR_INVALID_TOPOLOGY, WEFM_ERROR_INVALID_CONSTRAINT,
 *         WEFM_ERROR_SINGULAR, WEFM_ERROR_NOT_POSITIVE_DEFINITE, WEFM_ERROR_NOT_CONVERGED,
 *         WEFM_ERROR_CANCELLED, WEFM_ERROR_OUT_OF_MEMORY (also for options.memory_limit_mb), with the
 *         detail in wefm_face_last_error().
 */
WEFM_API wefm_status wefm_face_solve(wefm_face* face);
/** Ask a running solve to stop at its next check (thread-safe). The solve returns WEFM_ERROR_CANCELLED. */
WEFM_API wefm_status wefm_face_cancel(wefm_face* face);
/** Non-zero in *solved when a result is available (the result queries below then succeed). */
WEFM_API wefm_status wefm_face_has_result(const wefm_face* face, int32_t* solved);

/* ---- Results ------------------------------------------------------------------------------- */

/** UV of every use: 2 doubles per use, by the size-query protocol.
 *  WEFM_ERROR_INVALID_STATE before a successful solve (and after a change that cleared the result). */
WEFM_API wefm_status wefm_face_get_uv(wefm_face* face, double* uv, int64_t capacity, int64_t* count);
/** Decision per edge (wefm_edge_mode, AUTO resolved): 1 int32 per edge, non-repeated edges give FREE.
 *  Size-query protocol; WEFM_ERROR_INVALID_STATE without a result. */
WEFM_API wefm_status wefm_face_get_edge_modes(wefm_face* face, int32_t* modes, int64_t capacity, int64_t* count);
/** Score of each candidate mode tried for an edge: 5 doubles indexed by wefm_edge_mode (NaN = not tried).
 *  Size-query protocol; WEFM_ERROR_OUT_OF_RANGE for a bad edge, WEFM_ERROR_INVALID_STATE without a result. */
WEFM_API wefm_status wefm_face_get_edge_scores(wefm_face* face, int32_t edge, double* scores, int64_t capacity, int64_t* count);

/** Quality and cost of the last solve (wefm_face_get_report()); fill with wefm_report_init() first. */
typedef struct wefm_report {
  size_t struct_size;            /**< set by wefm_report_init() */
  double score;                  /**< METHOD §8: area-weighted mean of r^2 in [0, 1] (1 is perfect), minus 1
                                      if any triangle is flipped, minus 2 if the boundary self-intersects */
  int64_t flipped_triangles;     /**< triangles with negative UV area */
  int64_t boundary_intersections; /**< crossing pairs of boundary segments in UV */
  double area_distortion_mean;   /**< 3D-area weighted mean of |log(UV area / 3D area)| after area normalisation */
  double area_distortion_max;    /**< the largest of those per triangle */
  double angle_distortion_mean;  /**< 3D-area weighted mean of sigma_max/sigma_min of the Jacobian */
  double angle_distortion_max;   /**< the largest of those per triangle */
  double uv_area;                /**< total UV area as returned */
  double area_3d;                /**< total 3D area */
  double s;                      /**< s of the returned layout: the best-scoring iterate, which may be below the target */
  int32_t converged;             /**< non-zero when every rho fixed point converged */
  int32_t method;                /**< wefm_method used */
  int32_t s_steps;               /**< continuation steps taken */
  int32_t rho_iterations;        /**< total rho iterations over all steps */
  double rho_change;             /**< final relative rho change */
  int64_t symbolic_analyses;     /**< sparse symbolic analyses (orderings) */
  int64_t numeric_factorizations; /**< numeric Cholesky factorisations */
  int64_t solves;                /**< triangular solve passes with the factor (one per right-hand side) */
  int64_t iterative_iterations;  /**< PCG / roll-out sweep iterations */
  int32_t auto_cut;              /**< non-zero if the solve cut the face itself */
  int32_t degenerate_triangles;  /**< triangles regularised by min_beta */
  double time_topology, time_coefficients, time_assembly, time_analysis, time_factorization,
         time_solve, time_continuation, time_quality, time_total; /**< seconds, wall. Where the analysis
                                      runs beside the coefficients and assembly (see Threads),
                                      time_analysis is only the time the solve waited for it */
  double peak_memory_mb;         /**< process peak resident set size after the solve (0 if unknown) */
  int32_t min_beta_raised;       /**< non-zero: the first layout had flips or boundary overlaps and this
                                      one, solved again with min_beta 0.05, scored better */
  double boundary_unwind;        /**< 1, or < 1 when the first layout overlapped itself and this one aims
                                      gentle boundary turns at that fraction of their 3D value */
  int32_t auto_cut_edges;        /**< facet edges in the automatic cut (0 without one) */
  int32_t auto_cut_uncut_kept;   /**< annulus only: non-zero if the layout without the cut scored better
                                      and is returned; the cut's two sides then coincide (mode scar) */
  double auto_cut_length;        /**< 3D length of the automatic cut (0 without one) */
  double auto_cut_other_score;   /**< annulus only: score of the layout not returned (uncut, or cut if
                                      auto_cut_uncut_kept); NaN if not computed */
  double via_s;                  /**< 0, or 2 when the continuation to the target s ended invalid and this
                                      layout came back down to it from s = 2 */
  double boundary_unwind_weight; /**< 0, or the boundary-term weight of the unwinding retry that gave this
                                      layout (see boundary_unwind: 10, or 30 where 10 was not enough) */
  int32_t abandoned_steps;       /**< tentative continuation steps (longer than 1 in s, see s_step) given up
                                      where Gauss-Newton cut a step short, and taken again in steps of 1;
                                      their iterations count in rho_iterations, not in the step history */
} wefm_report;

/** Zero `report` and set struct_size = `struct_size` (the caller's sizeof); errors as wefm_options_init(). */
WEFM_API wefm_status wefm_report_init(wefm_report* report, size_t struct_size);
/**
 * Quality report, counters and timings of the current result.
 * @param face            the face.
 * @param[in,out] report  struct_size set (wefm_report_init()); only that many bytes are written.
 * @return WEFM_ERROR_INVALID_ARGUMENT (struct_size too small), WEFM_ERROR_INVALID_STATE (no result).
 */
WEFM_API wefm_status wefm_face_get_report(const wefm_face* face, wefm_report* report);
/** Per continuation step: 3 doubles (s, rho iterations, final rho change), by the size-query protocol.
 *  WEFM_ERROR_INVALID_STATE without a result. */
WEFM_API wefm_status wefm_face_get_step_history(const wefm_face* face, double* steps, int64_t capacity, int64_t* count);

/* ---- Mapping ------------------------------------------------------------------------------- */

/**
 * Map `n` UV points (2n doubles) to 3D (3n doubles). `point_status` (n int32, may be NULL) gets per
 * point: WEFM_OK (in the domain); WEFM_ERROR_OUTSIDE_DOMAIN (outside: mapped through the nearest
 * domain point; a point farther than 1e6 domain diameters, up to the largest double, through the
 * point at that distance in its direction); WEFM_ERROR_INVALID_ARGUMENT (a NaN or infinite
 * coordinate: its outputs are NaN). `triangles` (n int32, may be NULL) gets the containing triangle
 * or -1. Every point is mapped and given its status before the call returns.
 * @return WEFM_ERROR_INVALID_STATE (no result), WEFM_ERROR_INVALID_ARGUMENT (n < 0, or some point is
 *         not finite: the others are mapped all the same; the message counts them and names the first).
 */
WEFM_API wefm_status wefm_face_map_uv_to_3d(wefm_face* face, int64_t n, const double* uv, double* xyz,
                                            int32_t* point_status, int32_t* triangles);
/** Map `n` 3D points (3n doubles) to UV (2n doubles) through the closest point of the triangulation.
 *  Per-point statuses, triangles and return values as wefm_face_map_uv_to_3d(): WEFM_ERROR_OUTSIDE_DOMAIN
 *  for a point farther than 1e-6 of the mesh's bounding-box diagonal from the triangulation. */
WEFM_API wefm_status wefm_face_map_3d_to_uv(wefm_face* face, int64_t n, const double* xyz, double* uv,
                                            int32_t* point_status, int32_t* triangles);

/* ---- Output -------------------------------------------------------------------------------- */

/** Write the result as OBJ: v (3D), vt (UV per use) and f v/vt.
 *  @return WEFM_ERROR_INVALID_STATE (no result), WEFM_ERROR_IO (cannot write `path`). */
WEFM_API wefm_status wefm_face_write_obj(wefm_face* face, const char* path);

/* ============================================================================================= */
/* Meshing the domain (METHOD §9)                                                                */
/* ============================================================================================= */

/** A mesh of a solved domain mapped to 3D (opaque, reference counted). */
typedef struct wefm_domain_mesh wefm_domain_mesh;

/** wefm_mesh_options.type. */
typedef enum wefm_mesh_type {
  WEFM_MESH_FREE = 0,        /**< frontal-Delaunay triangles sized in 3D, then smoothing and optimisation */
  WEFM_MESH_TRANSFINITE = 1, /**< Coons patch on four corners, quads (or split triangles); with edge nodes set
                                  (wefm_face_set_edge_nodes) the sides carry those nodes and opposite sides
                                  must have as many (else WEFM_ERROR_UNSUPPORTED) */
  WEFM_MESH_AUTO = 2         /**< transfinite on `corners` where the caller gives them (a face with holes is
                                  not four-sided), else where the domain is four-sided (one loop; four
                                  vertices where its boundary turns left by 30 to 150 degrees, every other
                                  turn under 20), if the grid's worst quad has a scaled Jacobian of at least
                                  0.3; else free. wefm_mesh_report.transfinite says which, and
                                  automatic_fallback why not. Opposite sides with unlike counts of caller
                                  nodes, or a grid over max_elements, give the free mesh, not an error;
                                  corners that are not four distinct uses of the outer loop are an error
                                  (WEFM_ERROR_INVALID_ARGUMENT) */
} wefm_mesh_type;

/** wefm_mesh_report.automatic_fallback: why WEFM_MESH_AUTO made a free mesh. */
typedef enum wefm_automatic_fallback {
  WEFM_FALLBACK_NONE = 0,            /**< it made the grid, or WEFM_MESH_AUTO was not asked for */
  WEFM_FALLBACK_NOT_FOUR_SIDED = 1,  /**< no corners given and the domain is not four-sided, or holes */
  WEFM_FALLBACK_GRID_REFUSED = 2,    /**< the transfinite mesher refused the grid: opposite sides with
                                          unlike counts of caller nodes, or more than max_elements */
  WEFM_FALLBACK_POOR_GRID = 3        /**< the grid's worst quad was below a scaled Jacobian of 0.3
                                          (refused_grid_scaled_jacobian_min) */
} wefm_automatic_fallback;

/** wefm_mesh_options.elements: the elements of a free mesh. */
typedef enum wefm_elements {
  WEFM_ELEMENTS_TRIANGLES = 0,      /**< triangles only (nodes_per_element 3) */
  WEFM_ELEMENTS_QUAD_DOMINANT = 1,  /**< pairs of triangles made quads where the quad is good in 3D (scaled
                                         Jacobian >= 0.3, convex in UV); nodes_per_element 4, and a triangle
                                         left over has -1 as its fourth node */
  WEFM_ELEMENTS_QUADS = 2           /**< quad-dominant, then every element split into quads at its edge
                                         midpoints and centre (nodes_per_element 4, all quads, their sides
                                         about size / 2, as Gmsh's subdivision gives: ask for twice the size
                                         for quads of about `size`); the boundary gets a node at each
                                         segment's midpoint (of the 3D chord), so faces given the same edge
                                         nodes still share theirs */
} wefm_elements;

/** Options of wefm_face_mesh_domain(); fill with wefm_mesh_options_init() first. */
typedef struct wefm_mesh_options {
  size_t struct_size;
  int type;                  /**< wefm_mesh_type. Default FREE */
  double size;               /**< target 3D element size h (> 0). Required */
  int32_t corners[4];        /**< transfinite and automatic corners as vertex uses on the outer loop, -1 = detect. Default -1 */
  int quads;                 /**< transfinite: non-zero writes quads, zero splits each into two triangles. Default 1 */
  int smoothing_iterations;  /**< free meshes: smoothing passes accepted only if 3D quality improves (from the fourth, only nodes whose elements include one under Lo lambda 0.6), then min(this, 3) passes optimising sum log lambda. Default 5 */
  double corner_angle_deg;   /**< loop vertices turning more than this are kept as nodes. Default 30 */
  double min_angle_deg;      /**< angle bound in UV of the circumcentre refinement after the front. Default 28 */
  int64_t max_elements;      /**< refuse to exceed this many elements (0 = no cap). Default 0 */
  int elements;              /**< wefm_elements of a free mesh. Transfinite meshes follow `quads`; with
                                  quads and WEFM_ELEMENTS_QUADS their grid is halved both ways, the new
                                  boundary nodes at the 3D chords' midpoints as in a free all-quad mesh.
                                  Default WEFM_ELEMENTS_TRIANGLES */
  int split_chords;          /**< free meshes: non-zero splits, at its UV middle, every edge between two boundary
                                  nodes whose surface there lies more than a tenth of its length off the
                                  straight edge, however short (default 0: only edges of at least size / 2, a
                                  quarter of their length off). For a caller whose faces share two boundary
                                  nodes across a narrow or coarse part (the two halves of a thin tube, a half
                                  tube and its symmetry plane): both faces would otherwise make the same
                                  straight chord between them, an edge of four triangles in the welded mesh.
                                  Default 0 */
} wefm_mesh_options;

/** Quality and cost of a domain mesh (wefm_domain_mesh_get_report()); fill with wefm_mesh_report_init() first. */
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
  int64_t quads;                 /**< elements with four nodes (the rest are triangles) */
  double quad_area_fraction;     /**< the quads' share of the mesh's 3D area */
  int32_t transfinite;           /**< non-zero: a transfinite grid (WEFM_MESH_TRANSFINITE, or chosen by
                                      WEFM_MESH_AUTO); zero: a free mesh */
  int32_t automatic_fallback;    /**< wefm_automatic_fallback: why WEFM_MESH_AUTO made a free mesh */
  double refused_grid_scaled_jacobian_min;  /**< WEFM_FALLBACK_POOR_GRID: the worst quad of the grid not
                                                 kept; else 0 */
} wefm_mesh_report;

/** Fill `options` with the defaults (size must still be set); `struct_size` as for wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_options_init(wefm_mesh_options* options, size_t struct_size);
/** Zero `report` and set struct_size = `struct_size`; errors as wefm_options_init(). */
WEFM_API wefm_status wefm_mesh_report_init(wefm_mesh_report* report, size_t struct_size);

/**
 * Use caller-given 3D nodes along edge `edge` (3n doubles, in the edge's direction, including both end
 * vertices) instead of discretising it at the global size. The nodes must lie on the edge's facet chain.
 * Free and transfinite meshes both take them, so faces given the same nodes on a shared edge conform.
 */
WEFM_API wefm_status wefm_face_set_edge_nodes(wefm_face* face, int32_t edge, int64_t n, const double* xyz);
/** Forget every wefm_face_set_edge_nodes(): all edges are discretised at the global size again. */
WEFM_API wefm_status wefm_face_clear_edge_nodes(wefm_face* face);

/** Mesh the solved domain and map it to 3D. Needs a result (wefm_face_solve). The face's progress
 *  callback hears the stage "mesh" with the fraction done (0 at the start, 1 at the end) and may stop
 *  it as it stops a solve (WEFM_ERROR_CANCELLED), under the same re-entrancy rule. */
WEFM_API wefm_status wefm_face_mesh_domain(wefm_face* face, const wefm_mesh_options* options, wefm_domain_mesh** out);
/** Add a reference to `mesh` (each needs its own wefm_domain_mesh_release()). */
WEFM_API wefm_status wefm_domain_mesh_retain(wefm_domain_mesh* mesh);
/** Drop a reference; the last one frees the mesh. NULL is ignored. */
WEFM_API void wefm_domain_mesh_release(wefm_domain_mesh* mesh);
/** Node UV: 2 doubles per node. */
WEFM_API wefm_status wefm_domain_mesh_get_uv(const wefm_domain_mesh* mesh, double* uv, int64_t capacity, int64_t* count);
/** Node 3D positions: 3 doubles per node. */
WEFM_API wefm_status wefm_domain_mesh_get_xyz(const wefm_domain_mesh* mesh, double* xyz, int64_t capacity, int64_t* count);
/** Elements: nodes_per_element int32 per element, counter-clockwise in UV. With nodes_per_element 4, a
 *  fourth node of -1 marks a triangle (quad-dominant meshes, WEFM_ELEMENTS_QUAD_DOMINANT). */
WEFM_API wefm_status wefm_domain_mesh_get_elements(const wefm_domain_mesh* mesh, int32_t* nodes, int64_t capacity, int64_t* count);
/** Quality report of the mesh; `report` filled with wefm_mesh_report_init() first, only its first
 *  struct_size bytes are written. */
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
