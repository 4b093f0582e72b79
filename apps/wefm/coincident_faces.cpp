#include "coincident_faces.hpp"

#include <algorithm>
#include <cmath>

#include "cad_edge_nodes.hpp"

namespace wefm_cli {

FaceShape shape_of(const wefm_cad::CadFace& f) {
  FaceShape s{wefm_cad::face_area(f), {1e300, 1e300, 1e300, -1e300, -1e300, -1e300}, {0, 0, 0}};
  for (size_t v = 0; v + 2 < f.xyz.size(); v += 3)
    for (size_t c = 0; c < 3; ++c) s.box[c] = std::min(s.box[c], f.xyz[v + c]), s.box[c + 3] = std::max(s.box[c + 3], f.xyz[v + c]);
  for (size_t t = 0; t + 2 < f.triangles.size(); t += 3) {
    const double* a = &f.xyz[3 * static_cast<size_t>(f.triangles[t])];
    const double* b = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 1])];
    const double* c = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    s.normal[0] += u[1] * w[2] - u[2] * w[1], s.normal[1] += u[2] * w[0] - u[0] * w[2], s.normal[2] += u[0] * w[1] - u[1] * w[0];
  }
  return s;
}

// Per face, the earlier face it lies on (index + 1; that face lies on no earlier one), or 0.
std::vector<size_t> coincident_faces(const wefm_cad::CadModel& model) {
  const double tol = 1e-6 * model.bbox_diagonal;
  std::vector<FaceShape> shapes;
  for (const wefm_cad::CadFace& f : model.faces) shapes.push_back(shape_of(f));
  auto usable = [&](size_t i) { return model.faces[i].error.empty() && shapes[i].area > 0; };
  std::vector<size_t> order(shapes.size()), source(shapes.size(), 0);
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return shapes[a].box[0] < shapes[b].box[0]; });
  std::vector<std::vector<size_t>> earlier(shapes.size());  // per face, the earlier faces of its shape
  for (size_t k = 0; k < order.size(); ++k)
    for (size_t q = k + 1; q < order.size() && shapes[order[q]].box[0] - shapes[order[k]].box[0] <= tol; ++q) {
      const size_t i = std::min(order[k], order[q]), j = std::max(order[k], order[q]);
      if (!usable(i) || !usable(j) || std::fabs(shapes[i].area - shapes[j].area) > 1e-6 * shapes[j].area) continue;
      bool same = true;
      for (size_t c = 0; c < 6 && same; ++c) same = std::fabs(shapes[i].box[c] - shapes[j].box[c]) <= tol;
      if (same) earlier[j].push_back(i);
    }
  for (size_t j = 0; j < shapes.size(); ++j)
    for (size_t i : earlier[j])
      if (!source[i] && (!source[j] || i < source[j] - 1)) source[j] = i + 1;
  return source;
}


}  // namespace wefm_cli
