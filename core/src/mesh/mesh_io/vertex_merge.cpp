// Merging STL corners into shared vertices. Exact duplicates (the normal case: every corner of a
// closed STL appears about six times) go through a hash table on the coordinates in O(1) each;
// only the distinct positions are then compared with their neighbours within the tolerance, on a
// grid of cells twice the tolerance wide so that 8 cells, not 27, can hold a match.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "readers.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/mix64.hpp"

namespace wefm::io {

namespace {

std::uint64_t bits(double x) {
  if (x == 0) x = 0;  // -0 == 0 as the comparison below says, so it must hash alike
  std::uint64_t b;
  std::memcpy(&b, &x, 8);
  return b;
}

// Open addressing, linear probing; slots hold an index into `keys` or -1.
class Table {
 public:
  explicit Table(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    slots_.assign(cap, -1);
    mask_ = cap - 1;
  }
  // The slot for `hash` whose entry `same(index)` accepts, or the empty slot where it belongs.
  template <class Same>
  Index& find(std::uint64_t hash, Same same) {
    for (std::size_t s = hash & mask_;; s = (s + 1) & mask_) {
      Index& slot = slots_[s];
      if (slot < 0 || same(slot)) return slot;
    }
  }

 private:
  std::vector<Index> slots_;
  std::size_t mask_ = 0;
};

}  // namespace

ReadResult merge_corners(const std::vector<Vec3>& corners, double tol, const std::string& path) {
  ReadResult r;
  if (corners.empty()) fail(Errc::invalid_mesh, path + ": no triangles found");
  if (corners.size() > 0x7fffffffULL) fail(Errc::invalid_mesh, path + ": too many triangles");
  Vec3 lo = corners[0], hi = corners[0];
  for (const Vec3& c : corners) {
    if (!c.allFinite()) fail(Errc::invalid_mesh, path + ": a vertex has a NaN or infinite coordinate");
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const double diag = (hi - lo).norm();
  // Relative tolerances below 1e-15 are below double resolution; clamping also keeps cell indices
  // (extent / tolerance) far inside int64.
  const double eps = std::max(tol > 0 ? tol : 1e-9, 1e-15) * (diag > 0 ? diag : 1.0);
  const double cell = 2 * eps;

  // 1. Exact duplicates: each distinct position gets the id of its first corner's vertex.
  std::vector<Index> distinct;  // first corner of each distinct position, in order of appearance
  std::vector<Index> corner_to_distinct(corners.size());
  {
    Table exact(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const Vec3& c = corners[i];
      const std::uint64_t h = mix64(bits(c[0]) ^ mix64(bits(c[1]) ^ mix64(bits(c[2]))));
      Index& slot = exact.find(h, [&](Index d) { return corners[static_cast<std::size_t>(distinct[static_cast<std::size_t>(d)])] == c; });
      if (slot < 0) {
        slot = static_cast<Index>(distinct.size());
        distinct.push_back(static_cast<Index>(i));
      }
      corner_to_distinct[i] = slot;
    }
  }

  // 2. Distinct positions within eps of an earlier vertex join it (first come, first kept).
  std::vector<Index> distinct_to_vertex(distinct.size());
  {
    struct Key {
      std::int64_t x, y, z;
      bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    auto key_hash = [](const Key& k) {
      return mix64(static_cast<std::uint64_t>(k.x) ^ mix64(static_cast<std::uint64_t>(k.y) ^ mix64(static_cast<std::uint64_t>(k.z))));
    };
    std::vector<Key> cell_key;        // per occupied cell
    std::vector<Index> cell_first;    // per occupied cell: first vertex in it
    std::vector<Index> next_in_cell;  // per vertex: next vertex in the same cell, or -1
    Table cells(distinct.size());
    r.mesh.vertices.reserve(distinct.size());
    for (std::size_t d = 0; d < distinct.size(); ++d) {
      const Vec3& c = corners[static_cast<std::size_t>(distinct[d])];
      double f[3];
      Key home;
      for (int k = 0; k < 3; ++k) f[k] = (c[k] - lo[k]) / cell;
      home = {static_cast<std::int64_t>(std::floor(f[0])), static_cast<std::int64_t>(std::floor(f[1])), static_cast<std::int64_t>(std::floor(f[2]))};
      // A point within eps can only lie in this cell or the neighbour on the nearer side per axis.
      const std::int64_t side[3] = {f[0] - std::floor(f[0]) < 0.5 ? -1 : 1, f[1] - std::floor(f[1]) < 0.5 ? -1 : 1,
                                    f[2] - std::floor(f[2]) < 0.5 ? -1 : 1};
      Index found = -1;
      for (int m = 0; m < 8 && found < 0; ++m) {
        const Key k{home.x + ((m & 1) ? side[0] : 0), home.y + ((m & 2) ? side[1] : 0), home.z + ((m & 4) ? side[2] : 0)};
        const Index slot = cells.find(key_hash(k), [&](Index s) { return cell_key[static_cast<std::size_t>(s)] == k; });
        if (slot < 0) continue;
        for (Index v = cell_first[static_cast<std::size_t>(slot)]; v >= 0; v = next_in_cell[static_cast<std::size_t>(v)])
          if ((r.mesh.vertices[static_cast<std::size_t>(v)] - c).norm() <= eps) {
            found = v;
            break;
          }
      }
      if (found < 0) {
        found = static_cast<Index>(r.mesh.vertices.size());
        r.mesh.vertices.push_back(c);
        Index& slot = cells.find(key_hash(home), [&](Index s) { return cell_key[static_cast<std::size_t>(s)] == home; });
        if (slot < 0) {
          slot = static_cast<Index>(cell_key.size());
          cell_key.push_back(home);
          cell_first.push_back(-1);
        }
        next_in_cell.push_back(cell_first[static_cast<std::size_t>(slot)]);
        cell_first[static_cast<std::size_t>(slot)] = found;
      }
      distinct_to_vertex[d] = found;
    }
  }

  r.mesh.triangles.resize(corners.size() / 3);
  for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      r.mesh.triangles[t][k] = distinct_to_vertex[static_cast<std::size_t>(corner_to_distinct[3 * t + k])];
  // Every corner that did not create a vertex was merged into one, exact matches included.
  r.merged_vertices = static_cast<std::int64_t>(corners.size()) - static_cast<std::int64_t>(r.mesh.vertices.size());
  return r;
}

}  // namespace wefm::io
