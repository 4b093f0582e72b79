#include "cad_face_files.hpp"

#include <cstdio>
#include <sstream>
#include <nlohmann/json.hpp>

namespace wefm_cad {

std::string face_obj_text(const CadFace& face, const std::string& model_path) {
  std::ostringstream out;
  std::string model = model_path;  // a newline in the name would end the comment
  for (char& c : model) c = c == '\n' || c == '\r' ? ' ' : c;
  out << "# face " << face.index << " (" << face.surface_type << ") of " << model << "\n";
  char buf[96];
  for (size_t i = 0; i + 2 < face.xyz.size(); i += 3) {
    // %.17g: doubles read back bit for bit.
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", face.xyz[i], face.xyz[i + 1], face.xyz[i + 2]);
    out << buf;
  }
  for (size_t t = 0; t + 2 < face.triangles.size(); t += 3)
    out << "f " << face.triangles[t] + 1 << ' ' << face.triangles[t + 1] + 1 << ' ' << face.triangles[t + 2] + 1 << '\n';
  return out.str();
}

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
