// Mesh file reading and writing (core/src/mesh/mesh_io*): every accepted OBJ form, exact doubles from
// OFF and PLY (ASCII and binary, both byte orders), STL corner merging and its count, error
// messages with line numbers, and the UV OBJ writer reading back exactly.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/mesh_io.hpp"

using namespace wefm;

namespace {

// Doubles that float32 would change: a reader going through float fails these comparisons.
constexpr double kA = 0.12345678901234567, kB = 100000000.123, kC = -2.5e-7;

std::string temp_path(const std::string& name) {
  static const std::string dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("wefm_mesh_io_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  return dir + "/" + name;
}

std::string write_file(const std::string& name, const std::string& bytes) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

std::string error_of(const std::string& path, double tol = 0) {
  try {
    read_mesh(path, tol);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

Errc code_of(const std::string& path) {
  try {
    read_mesh(path, 0);
  } catch (const Error& e) {
    return e.code();
  }
  return Errc::internal;
}

template <class T>
void put(std::string& s, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  s.append(b, sizeof(T));
}

}  // namespace

TEST_CASE("OBJ: corner forms, negative and forward indices, polygons, ignored statements, CRLF") {
  const std::string p = write_file("forms.obj",
                                   "# comment\r\n"
                                   "o thing\n"
                                   "f 1 2 3\n"  // forward reference: vertices come later
                                   "v 0 0 0\n"
                                   "  v\t1 0 0 1.0\n"  // leading blanks, tab, w component
                                   "v 1 +1 0\r\n"
                                   "v 0 1 0\n"
                                   "vt 0.5 0.5\n"
                                   "vn 0 0 1\n"
                                   "usemtl m\n"
                                   "s off\n"
                                   "f 1/1 2/1/1 3//1\n"
                                   "f -4 -2 -1\n"
                                   "f 1 2 3 4\n"  // quad: two triangles
                                   "l 1 2\n"
                                   "f 2 3 4");  // no final newline
  const ReadResult r = read_mesh(p, 0);
  REQUIRE(r.mesh.vertices.size() == 4);
  CHECK(r.mesh.vertices[2] == Vec3(1, 1, 0));
  REQUIRE(r.mesh.triangles.size() == 6);
  CHECK(r.mesh.triangles[0] == Tri{0, 1, 2});
  CHECK(r.mesh.triangles[1] == Tri{0, 1, 2});
  CHECK(r.mesh.triangles[2] == Tri{0, 2, 3});  // -4 -2 -1 after four vertices
  CHECK(r.mesh.triangles[3] == Tri{0, 1, 2});
  CHECK(r.mesh.triangles[4] == Tri{0, 2, 3});
  CHECK(r.mesh.triangles[5] == Tri{1, 2, 3});
  CHECK(r.merged_vertices == 0);
}

TEST_CASE("OBJ: doubles are exact") {
  const ReadResult r = read_mesh(write_file("exact.obj", "v 0.12345678901234567 100000000.123 -2.5e-7\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 0);
  CHECK(r.mesh.vertices[0][0] == kA);
  CHECK(r.mesh.vertices[0][1] == kB);
  CHECK(r.mesh.vertices[0][2] == kC);
}

TEST_CASE("OBJ: errors name the file and line") {
  CHECK(error_of(write_file("e1.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n")).find("e1.obj:2: bad vertex coordinate") != std::string::npos);
  CHECK(error_of(write_file("e2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 x 3\n")).find("e2.obj:5: bad face index") != std::string::npos);
  CHECK(error_of(write_file("e3.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n")).find("e3.obj:4: face index 0 is out of range") != std::string::npos);
  CHECK(error_of(write_file("e4.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n")).find("e4.obj:4: face index -4 is out of range") != std::string::npos);
  CHECK(error_of(write_file("e5.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")).find("e5.obj:3: a face needs at least 3 vertices") != std::string::npos);
  CHECK(error_of(write_file("e6.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")).find("face index 9 exceeds the 3 vertices") != std::string::npos);
  CHECK(error_of(write_file("e7.obj", "v 0 0 0\n")).find("no faces found") != std::string::npos);
  CHECK(error_of(write_file("e8.obj", "v 0 0 0\nf 1 2 99999999999999999999\n")).find("e8.obj:2: bad face index") != std::string::npos);
  CHECK(error_of(temp_path("missing.obj")).find("cannot open") != std::string::npos);
  CHECK(error_of(write_file("x.xyz", "")).find("unsupported mesh format") != std::string::npos);
}

TEST_CASE("mesh files: a file that cannot be read is an I/O error, malformed content an invalid mesh") {
  CHECK(code_of(temp_path("missing.obj")) == Errc::io);
  std::filesystem::create_directories(temp_path("dir.obj"));
  CHECK(code_of(temp_path("dir.obj")) == Errc::io);
  CHECK(code_of(write_file("m1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")) == Errc::invalid_mesh);
  CHECK(code_of(write_file("m2.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n")) == Errc::invalid_mesh);
  CHECK(code_of(write_file("m3.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n")) == Errc::invalid_mesh);
  CHECK(code_of(write_file("m4.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n0 0 0\n")) == Errc::invalid_mesh);
  CHECK(code_of(write_file("m5.stl", "not an stl")) == Errc::invalid_mesh);
  CHECK(code_of(write_file("m6.xyz", "")) == Errc::unsupported);
}

TEST_CASE("OFF: doubles are exact, polygons, colours and comments skipped") {
  const std::string p = write_file("a.off",
                                   "COFF\n# comment\n5 2 0\n"
                                   "0.12345678901234567 100000000.123 -2.5e-7 255 0 0 255\n"
                                   "1 0 0 0 0 0 255\n2 1 0 0 0 0 255\n1 2 0 0 0 0 255\n0 1 0 0 0 0 255\n"
                                   "3 0 1 2 255 0 0\n"
                                   "4 0 2 3 4\n");
  const ReadResult r = read_mesh(p, 0);
  REQUIRE(r.mesh.vertices.size() == 5);
  CHECK(r.mesh.vertices[0][0] == kA);
  CHECK(r.mesh.vertices[0][1] == kB);
  CHECK(r.mesh.vertices[0][2] == kC);
  REQUIRE(r.mesh.triangles.size() == 3);
  CHECK(r.mesh.triangles[2] == Tri{0, 3, 4});
  CHECK(error_of(write_file("b.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")).find("b.off:6: face 0: vertex index 7 is out of range") !=
        std::string::npos);
  CHECK(error_of(write_file("c.off", "OFF BINARY\n")).find("binary OFF") != std::string::npos);
  CHECK(read_mesh(write_file("d.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), 0).mesh.triangles.size() == 1);
  // A header promising far more than the file holds is refused before anything is allocated.
  CHECK(error_of(write_file("huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n")).find("truncated file?") != std::string::npos);
}

TEST_CASE("PLY ASCII: doubles are exact, extra properties and elements skipped") {
  const std::string p = write_file("a.ply",
                                   "ply\nformat ascii 1.0\ncomment made by hand\n"
                                   "element vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\n"
                                   "element face 1\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
                                   "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
                                   "end_header\n"
                                   "0.12345678901234567 100000000.123 -2.5e-7 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n"
                                   "4 0 1 2 3 7\n"
                                   "0 1\n");
  const ReadResult r = read_mesh(p, 0);
  REQUIRE(r.mesh.vertices.size() == 4);
  CHECK(r.mesh.vertices[0][0] == kA);
  CHECK(r.mesh.vertices[0][1] == kB);
  CHECK(r.mesh.vertices[0][2] == kC);
  CHECK(r.mesh.triangles.size() == 2);
}

TEST_CASE("PLY binary, both byte orders: doubles are exact") {
  for (bool big : {false, true}) {
    CAPTURE(big);
    std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\n"
                    "element face 1\nproperty uchar flags\nproperty list uchar uint vertex_indices\nend_header\n";
    const double xyz[9] = {kA, kB, kC, 1, 0, 0, 0, 1, 0};
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 3; ++k) put(s, xyz[3 * v + k], big);
      put(s, 0.5f, big);
    }
    put(s, std::uint8_t{1});
    put(s, std::uint8_t{3});
    for (std::uint32_t i : {0u, 1u, 2u}) put(s, i, big);
    const ReadResult r = read_mesh(write_file(big ? "big.ply" : "little.ply", s), 0);
    REQUIRE(r.mesh.vertices.size() == 3);
    CHECK(r.mesh.vertices[0][0] == kA);
    CHECK(r.mesh.vertices[0][1] == kB);
    CHECK(r.mesh.vertices[0][2] == kC);
    REQUIRE(r.mesh.triangles.size() == 1);
    CHECK(r.mesh.triangles[0] == Tri{0, 1, 2});
  }
  CHECK(error_of(write_file("trunc.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nend_header\n1234"))
            .find("truncated file?") != std::string::npos);
}

TEST_CASE("STL: shared corners merge and merged_vertices counts every merge, exact ones included") {
  // A unit cube: 12 triangles, 36 corners, 8 vertices, so 28 corners merged.
  const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int tri[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::string ascii = "solid cube\n";
  std::string binary(80, ' ');
  put(binary, std::uint32_t{12});
  for (const auto& t : tri) {
    ascii += " facet normal 0 0 0\n  outer loop\n";
    for (float n : {0.f, 0.f, 0.f}) put(binary, n);
    for (int k = 0; k < 3; ++k) {
      ascii += "   vertex " + std::to_string(c[t[k]][0]) + " " + std::to_string(c[t[k]][1]) + " " + std::to_string(c[t[k]][2]) + "\n";
      for (int a = 0; a < 3; ++a) put(binary, static_cast<float>(c[t[k]][a]));
    }
    ascii += "  endloop\n endfacet\n";
    put(binary, std::uint16_t{0});
  }
  ascii += "endsolid cube\n";
  for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"cube_ascii.stl", ascii}, {"cube_binary.stl", binary}}) {
    CAPTURE(name);
    const ReadResult r = read_mesh(write_file(name, bytes), 0);
    CHECK(r.mesh.vertices.size() == 8);
    CHECK(r.mesh.triangles.size() == 12);
    CHECK(r.merged_vertices == 28);
    // Corner order is kept: the first triangle's corners are the first three vertices.
    CHECK(r.mesh.triangles[0] == Tri{0, 1, 2});
  }
}

TEST_CASE("STL: corners within the tolerance merge, farther ones do not") {
  // Two triangles sharing an edge whose copies differ by 1e-12 (bounding-box diagonal ~1.4).
  const std::string s = "solid t\n"
                        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                        "facet normal 0 0 1\nouter loop\nvertex 1.000000000001 0 0\nvertex 1 1 0\nvertex 0 1.000000000001 0\nendloop\nendfacet\n"
                        "endsolid t\n";
  const std::string p = write_file("near.stl", s);
  const ReadResult merged = read_mesh(p, 1e-9);
  CHECK(merged.mesh.vertices.size() == 4);
  CHECK(merged.merged_vertices == 2);
  const ReadResult apart = read_mesh(p, 1e-14);
  CHECK(apart.mesh.vertices.size() == 6);
  CHECK(apart.merged_vertices == 0);
}

TEST_CASE("write_obj_uv reads back exactly") {
  TriMesh m;
  m.vertices = {Vec3(kA, kB, kC), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  m.triangles = {Tri{0, 1, 2}, Tri{0, 2, 3}};
  const Topology tp = build_topology(m, TopologySpec{});
  VectorXc uv(tp.use_count);
  for (Index u = 0; u < tp.use_count; ++u) uv[u] = Complex(kA * u, -kB / (u + 1));
  const std::string p = temp_path("uv.obj");
  write_obj_uv(p, m, tp, uv);
  const ReadResult r = read_mesh(p, 0);
  REQUIRE(r.mesh.vertices.size() == 4);
  for (size_t v = 0; v < 4; ++v) CHECK(r.mesh.vertices[v] == m.vertices[v]);
  CHECK(r.mesh.triangles == m.triangles);
  std::ifstream in(p);
  std::string line;
  Index u = 0;
  while (std::getline(in, line))
    if (line.rfind("vt ", 0) == 0) {
      double a = 0, b = 0;
      REQUIRE(std::sscanf(line.c_str(), "vt %lf %lf", &a, &b) == 2);
      CHECK(a == uv[u].real());
      CHECK(b == uv[u].imag());
      ++u;
    }
  CHECK(u == tp.use_count);
}
