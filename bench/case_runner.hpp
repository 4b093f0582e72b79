#pragma once
// One benchmark case, run inside the current process and described as JSON. The driver starts a
// fresh process per case so that each peak-memory figure belongs to that case alone.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "face_generator.hpp"

namespace wefm_bench {

using Json = nlohmann::ordered_json;

// wefm through its public C API: set mesh, build topology, solve at `s`, per-stage times from the
// solve report plus the wall time between progress-callback stages.
Json run_wefm_case(Shape shape, int64_t size, double s, int threads);

// The cotangent-Laplacian floor (real, and complex when `complex_arithmetic`).
Json run_floor_case(Shape shape, int64_t size, bool complex_arithmetic);

// File I/O on the face, in `work_dir` (page cache warm): OBJ and binary STL reading through
// wefm_mesh_read, and the UV OBJ the `wefm` tool writes (its own writer, apps/wefm/mesh_formats.cpp).
Json run_io_case(Shape shape, int64_t size, const std::string& work_dir);

}  // namespace wefm_bench
