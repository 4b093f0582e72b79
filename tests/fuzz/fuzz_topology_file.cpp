// libFuzzer target: the CLI's topology-file parser and writer (apps/wefm/topology_file.cpp,
// `--topology`, `--write-topology`, topo.json). The bytes are the file. Properties: the status is 0,
// 3 or 4 and a failure names the file; a file that parses has consistent arrays (loops name edges
// that exist, the outer loop is a loop or -1); writing it and reading it back gives the same
// topology (ids, chains, modes, loops, outer loop).
#include <string>
#include <vector>

#include "fuzz_files.hpp"
#include "topology_file.hpp"

using wefm_fuzz::violated;

namespace {

void check_consistent(const wefm_cli::TopologyFile& t) {
  const size_t n = t.ids.size();
  if (t.chains.size() != n || t.modes.size() != n) violated("read_topology_file", "per-edge arrays of different sizes");
  if (t.loop_edges.size() != t.loop_reversed.size()) violated("read_topology_file", "loop arrays of different sizes");
  for (size_t l = 0; l < t.loop_edges.size(); ++l) {
    if (t.loop_edges[l].empty() || t.loop_edges[l].size() != t.loop_reversed[l].size())
      violated("read_topology_file", "an empty loop or a loop without its reversed flags");
    for (int32_t e : t.loop_edges[l])
      if (e < 0 || static_cast<size_t>(e) >= n) violated("read_topology_file", "a loop names an edge that is not there");
  }
  if (t.outer_loop < -1 || t.outer_loop >= static_cast<long long>(t.loop_edges.size()))
    violated("read_topology_file", "outer_loop is not a loop");
  for (const auto& chain : t.chains)
    for (int32_t v : chain)
      if (v < 0) violated("read_topology_file", "a negative vertex index");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string in = wefm_fuzz::write_temp_file("in.json", data, size);
  const std::string out = wefm_fuzz::temp_path("out.json");
  wefm_cli::TopologyFile topo;
  std::string error;
  if (!wefm_fuzz::cli_read_ok(wefm_cli::read_topology_file(in, topo, error), error, in, "read_topology_file")) return 0;
  check_consistent(topo);
  if (wefm_cli::write_topology_file(out, topo, error) != 0) violated("write_topology_file", error.c_str());
  wefm_cli::TopologyFile back;
  if (wefm_cli::read_topology_file(out, back, error) != 0) violated("topology round trip", error.c_str());
  if (back.ids != topo.ids || back.chains != topo.chains || back.modes != topo.modes ||
      back.loop_edges != topo.loop_edges || back.loop_reversed != topo.loop_reversed ||
      back.outer_loop != topo.outer_loop)
    violated("topology round trip", "the file written reads back as another topology");
  return 0;
}
