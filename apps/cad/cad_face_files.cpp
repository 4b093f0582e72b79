#include "cad_face_files.hpp"

#include <nlohmann/json.hpp>

namespace wefm_cad {

std::string face_topology_text(const CadFace& face, const std::string& model_path) {
  nlohmann::ordered_json doc;
  nlohmann::ordered_json edges = nlohmann::ordered_json::array();
  for (const CadEdge& e : face.edges) {
    nlohmann::ordered_json j;
    j["id"] = e.id;
    j["vertices"] = e.vertices;
    j["seam"] = e.seam;
    j["curve_type"] = e.curve_type;
    j["degenerated"] = e.degenerated;
    edges.push_back(std::move(j));
  }
  doc["edges"] = std::move(edges);
  nlohmann::ordered_json loops = nlohmann::ordered_json::array();
  for (const auto& loop : face.loops) {
    nlohmann::ordered_json l = nlohmann::ordered_json::array();
    for (const CadEdgeUse& u : loop) l.push_back({{"edge", face.edges[static_cast<size_t>(u.edge)].id}, {"reversed", u.reversed}});
    loops.push_back(std::move(l));
  }
  doc["loops"] = std::move(loops);
  doc["outer_loop"] = face.outer_loop;
  doc["surface_type"] = face.surface_type;
  doc["model"] = model_path;
  doc["face_index"] = face.index;
  doc["source"] = "wefm model (Open CASCADE import)";
  return doc.dump(1) + '\n';
}

}  // namespace wefm_cad
