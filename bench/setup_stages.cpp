// wefm-bench-setup FACE.obj [THREADS] [REPEATS]: the O(n) stages of a solve timed one by one on the
// core (reading, mesh statistics, validation, topology, coefficients, assembly both ways, writing),
// each the minimum over REPEATS runs (default 3) of wall and process CPU time, so that a loaded
// machine still gives comparable CPU figures. Prints a byte hash of K so that runs with different
// thread counts can be compared for bit-identity.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>

#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/method/energy_assembler.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/mesh_io.hpp"

using namespace wefm;

namespace {

double wall() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
double cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int repeats = 3;

void stage(const char* name, const std::function<void()>& run) {
  double best_wall = 1e300, best_cpu = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const double w0 = wall(), c0 = cpu();
    run();
    best_wall = std::min(best_wall, wall() - w0);
    best_cpu = std::min(best_cpu, cpu() - c0);
  }
  std::printf("%-40s wall %8.4f s   cpu %8.4f s\n", name, best_wall, best_cpu);
}

std::uint64_t fnv(const void* data, size_t bytes, std::uint64_t h = 1469598103934665603ull) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: wefm-bench-setup FACE.obj [THREADS] [REPEATS]\n");
    return 2;
  }
  const std::string path = argv[1];
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  if (argc > 3) repeats = std::max(1, std::atoi(argv[3]));
  try {
    ReadResult rr;
    stage("read_mesh (OBJ)", [&] { rr = read_mesh(path, 0.0); });
    const TriMesh& m = rr.mesh;
    std::printf("%zu vertices, %zu triangles, threads %d, best of %d\n", m.vertices.size(), m.triangles.size(), threads, repeats);
    stage("compute_stats (wefm_mesh_get_info)", [&] { (void)compute_stats(m); });
    HalfEdges he;
    stage("validate_mesh (wefm_face_set_mesh)", [&] { he = validate_mesh(m); });
    Topology tp;
    stage("build_topology, half-edges given", [&] { tp = build_topology(m, TopologySpec{}, &he); });
    stage("build_topology, half-edges built", [&] { tp = build_topology(m, TopologySpec{}); });
    Coefficients c;
    stage("compute_coefficients", [&] { c = compute_coefficients(m, tp, true, 1e-3, threads); });
    std::vector<Complex> sigma;
    stage("compute_sigma", [&] { sigma = compute_sigma(c, {}, 0.0, threads); });
    SpMatC B, A, K, D;
    stage("assemble_boundary_operator", [&] { B = assemble_boundary_operator(m, tp, c, 1.0); });
    stage("assemble_surface_operator (A)", [&] { A = assemble_surface_operator(tp, c, sigma, 0.5, Residual::PerHalfEdge, threads); });
    stage("assemble_energy(A, B) (A^H A + B^H B)", [&] { K = assemble_energy(A, &B, threads); });
    A = SpMatC();
    stage("assemble_energy(topology, ...) (direct)", [&] { D = assemble_energy(tp, c, sigma, 0.5, Residual::PerHalfEdge, &B, threads); });
    std::vector<double> w;
    stage("  of which compute_weights", [&] { w = compute_weights(tp, c, 0.5, threads); });
    stage("  of which EnergyAssembler (pattern)", [&] { EnergyAssembler pattern(tp, &B, threads); });
    const EnergyAssembler pattern(tp, &B, threads);
    stage("  of which EnergyAssembler::assemble", [&] { (void)pattern.assemble(w, sigma, threads); });
    const size_t nz = static_cast<size_t>(D.nonZeros());
    std::uint64_t h = fnv(D.valuePtr(), nz * sizeof(Complex));
    h = fnv(D.innerIndexPtr(), nz * sizeof(int), h);
    std::printf("K: %zu non-zeros, |K - A^H A - B^H B| / |K| = %.2e, byte hash %016llx\n", nz, (D - K).norm() / K.norm(),
                static_cast<unsigned long long>(h));
    const VectorXc uv = VectorXc::Zero(tp.use_count);
    const std::string out = path + ".setup-bench.obj";
    stage("write_obj_uv", [&] { write_obj_uv(out, m, tp, uv); });
    std::remove(out.c_str());
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
