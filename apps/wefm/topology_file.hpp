#pragma once
// JSON face topology (the topo.json schema of /work/shared/data/real): edges as vertex chains with
// model-wide ids, loops as ordered {edge, reversed} uses, the outer loop and optional per-edge modes.
// Ids are arbitrary integers; the library numbers edges 0..n-1 in the order they are added, so the
// file order is the library order and `ids` maps back.
#include <cstdint>
#include <string>
#include <vector>

namespace wefm_cli {

struct TopologyFile {
  std::vector<long long> ids;                 // per edge, the file's id
  std::vector<std::vector<int32_t>> chains;   // per edge, its vertex chain
  std::vector<int> modes;                     // per edge, wefm_edge_mode or -1 when not given
  std::vector<int> repeated;                  // per edge, 1/0 when written by us, -1 unknown (write only)
  std::vector<std::vector<int32_t>> loop_edges;     // per loop, edge indices (0..n-1, not ids)
  std::vector<std::vector<int32_t>> loop_reversed;  // per loop, 0/1
  int outer_loop = -1;                        // -1 = not given / automatic

  // Index of an edge id, -1 if unknown.
  long long index_of(long long id) const;
};

// Parses the file. Returns 0, or an exit code (3 unreadable, 4 malformed) with a message that names
// the file and the edge (by id) or loop (by index) at fault. Unknown fields are ignored.
int read_topology_file(const std::string& path, TopologyFile& topo, std::string& error);

// Writes the same schema (plus "repeated" per edge). Returns 0 or 3 with a message.
int write_topology_file(const std::string& path, const TopologyFile& topo, std::string& error);

}  // namespace wefm_cli
