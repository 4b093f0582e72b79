#include "topology_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "exit_codes.hpp"
#include "output_file.hpp"
#include "names.hpp"

namespace wefm_cli {

using nlohmann::json;

long long TopologyFile::index_of(long long id) const {
  for (size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == id) return static_cast<long long>(i);
  return -1;
}

namespace {

bool is_index(const json& v) {
  return v.is_number_integer() && v.get<long long>() >= 0 && v.get<long long>() <= 2147483647LL;
}

// Parse failures are thrown as this message and turned into exit code 4 with the file name.
struct Bad {
  std::string what;
};

std::string edge_name(size_t k, const json& e) {
  std::string s = "edge #" + std::to_string(k);
  if (e.is_object() && e.contains("id") && e["id"].is_number_integer())
    s += " (id " + std::to_string(e["id"].get<long long>()) + ")";
  return s;
}

void parse(const json& doc, TopologyFile& topo) {
  if (!doc.is_object()) throw Bad{"the top level must be an object with 'edges' and 'loops'"};
  if (!doc.contains("edges") || !doc["edges"].is_array()) throw Bad{"missing array 'edges'"};
  std::unordered_map<long long, int32_t> index;
  const json& edges = doc["edges"];
  for (size_t k = 0; k < edges.size(); ++k) {
    const json& e = edges[k];
    if (!e.is_object()) throw Bad{edge_name(k, e) + ": must be an object"};
    if (!e.contains("id") || !e["id"].is_number_integer()) throw Bad{edge_name(k, e) + ": missing integer 'id'"};
    const long long id = e["id"].get<long long>();
    if (!index.emplace(id, static_cast<int32_t>(k)).second)
      throw Bad{edge_name(k, e) + ": id " + std::to_string(id) + " used by an earlier edge too"};
    if (!e.contains("vertices") || !e["vertices"].is_array() || e["vertices"].empty())
      throw Bad{edge_name(k, e) + ": 'vertices' must be a non-empty array of vertex indices"};
    std::vector<int32_t> chain;
    chain.reserve(e["vertices"].size());
    for (const json& v : e["vertices"]) {
      if (!is_index(v)) throw Bad{edge_name(k, e) + ": 'vertices' holds " + v.dump() + ", not a vertex index"};
      chain.push_back(v.get<int32_t>());
    }
    int mode = -1;
    if (e.contains("mode") && !e["mode"].is_null()) {
      if (!e["mode"].is_string() || !parse_edge_mode(e["mode"].get<std::string>(), mode))
        throw Bad{edge_name(k, e) + ": 'mode' must be auto, free, periodic, scar or rotational, not " +
                  e["mode"].dump()};
    }
    topo.ids.push_back(id);
    topo.chains.push_back(std::move(chain));
    topo.modes.push_back(mode);
    topo.repeated.push_back(-1);
  }
  if (!doc.contains("loops") || !doc["loops"].is_array()) throw Bad{"missing array 'loops'"};
  const json& loops = doc["loops"];
  for (size_t l = 0; l < loops.size(); ++l) {
    const std::string name = "loop " + std::to_string(l);
    if (!loops[l].is_array() || loops[l].empty()) throw Bad{name + ": must be a non-empty array of edge uses"};
    std::vector<int32_t> es, rs;
    for (size_t j = 0; j < loops[l].size(); ++j) {
      const json& u = loops[l][j];
      const std::string where = name + ", use " + std::to_string(j);
      if (!u.is_object() || !u.contains("edge") || !u["edge"].is_number_integer())
        throw Bad{where + ": expected {\"edge\": id, \"reversed\": bool}"};
      const auto it = index.find(u["edge"].get<long long>());
      if (it == index.end())
        throw Bad{where + ": edge id " + std::to_string(u["edge"].get<long long>()) + " is not in 'edges'"};
      bool reversed = false;
      if (u.contains("reversed")) {
        const json& r = u["reversed"];
        if (r.is_boolean()) reversed = r.get<bool>();
        else if (r.is_number_integer()) reversed = r.get<long long>() != 0;
        else throw Bad{where + ": 'reversed' must be true or false"};
      }
      es.push_back(it->second);
      rs.push_back(reversed ? 1 : 0);
    }
    topo.loop_edges.push_back(std::move(es));
    topo.loop_reversed.push_back(std::move(rs));
  }
  if (doc.contains("outer_loop") && !doc["outer_loop"].is_null()) {
    const json& o = doc["outer_loop"];
    if (!o.is_number_integer() || o.get<long long>() < -1 ||
        o.get<long long>() >= static_cast<long long>(topo.loop_edges.size()))
      throw Bad{"'outer_loop' " + o.dump() + " is not a loop index (there are " +
                std::to_string(topo.loop_edges.size()) + " loops)"};
    topo.outer_loop = o.get<int>();
  }
}

}  // namespace

int read_topology_file(const std::string& path, TopologyFile& topo, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open topology file: " + std::strerror(errno);
    return kExitIo;
  }
  json doc = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) {
    error = path + ": not valid JSON";
    return kExitInvalid;
  }
  try {
    parse(doc, topo);
  } catch (const Bad& bad) {
    error = path + ": " + bad.what;
    return kExitInvalid;
  }
  return kExitOk;
}

int write_topology_file(const std::string& path, const TopologyFile& topo, std::string& error) {
  nlohmann::ordered_json doc;
  auto& edges = doc["edges"] = nlohmann::ordered_json::array();
  for (size_t k = 0; k < topo.chains.size(); ++k) {
    nlohmann::ordered_json e;
    e["id"] = topo.ids[k];
    e["vertices"] = topo.chains[k];
    if (k < topo.repeated.size() && topo.repeated[k] >= 0) e["repeated"] = topo.repeated[k] != 0;
    if (k < topo.modes.size() && topo.modes[k] >= 0) e["mode"] = edge_mode_name(topo.modes[k]);
    edges.push_back(std::move(e));
  }
  auto& loops = doc["loops"] = nlohmann::ordered_json::array();
  for (size_t l = 0; l < topo.loop_edges.size(); ++l) {
    auto loop = nlohmann::ordered_json::array();
    for (size_t j = 0; j < topo.loop_edges[l].size(); ++j)
      loop.push_back({{"edge", topo.ids[static_cast<size_t>(topo.loop_edges[l][j])]},
                      {"reversed", topo.loop_reversed[l][j] != 0}});
    loops.push_back(std::move(loop));
  }
  doc["outer_loop"] = topo.outer_loop;
  return write_file_atomically(path, doc.dump(1) + '\n', error);
}

}  // namespace wefm_cli
