/* Cross-language check, C side: read a mesh in the plain text format written by
 * tests/python/test_crosslang.py, flatten it with default options, write the UVs with %.17g. */
#include <stdio.h>
#include <stdlib.h>
#include <wefm/wefm.h>

static int fail(const char* what, wefm_face* face) {
  fprintf(stderr, "%s: %s\n", what, face ? wefm_face_last_error(face) : wefm_last_error());
  return 1;
}

int main(int argc, char** argv) {
  if (argc != 3) { fprintf(stderr, "usage: %s MESH.txt UV.txt\n", argv[0]); return 2; }
  FILE* in = fopen(argv[1], "r");
  long nv, nt;
  if (!in || fscanf(in, "%ld %ld", &nv, &nt) != 2) { fprintf(stderr, "cannot read %s\n", argv[1]); return 2; }
  double* xyz = malloc(sizeof(double) * 3 * (size_t)nv);
  int32_t* tri = malloc(sizeof(int32_t) * 3 * (size_t)nt);
  for (long i = 0; i < 3 * nv; ++i) if (fscanf(in, "%lf", &xyz[i]) != 1) return 2;
  for (long i = 0; i < 3 * nt; ++i) if (fscanf(in, "%d", &tri[i]) != 1) return 2;
  fclose(in);

  wefm_face* face = NULL;
  if (wefm_face_create(&face) != WEFM_OK) return fail("create", NULL);
  if (wefm_face_set_mesh(face, nv, xyz, nt, tri) != WEFM_OK) return fail("set_mesh", face);
  if (wefm_face_solve(face) != WEFM_OK) return fail("solve", face);
  int64_t count = 0;
  if (wefm_face_get_uv(face, NULL, 0, &count) != WEFM_OK) return fail("get_uv size", face);
  double* uv = malloc(sizeof(double) * (size_t)count);
  if (wefm_face_get_uv(face, uv, count, &count) != WEFM_OK) return fail("get_uv", face);

  FILE* out = fopen(argv[2], "w");
  if (!out) { fprintf(stderr, "cannot write %s\n", argv[2]); return 2; }
  for (int64_t i = 0; i < count; i += 2) fprintf(out, "%.17g %.17g\n", uv[i], uv[i + 1]);
  fclose(out);
  wefm_face_release(face);
  free(uv); free(xyz); free(tri);
  return 0;
}
