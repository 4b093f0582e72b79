/* A plain C program over the C API: every group of functions once, good and bad calls, all handles
 * released. Run under valgrind memcheck (ctest robust.valgrind_capi) it must report no error and no
 * definite leak. Usage: wefm_capi_smoke MESH.obj OUTDIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <wefm/wefm.h>

static int failures = 0;
#define EXPECT(cond)                                                  \
  do {                                                                \
    if (!(cond)) {                                                    \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                     \
    }                                                                 \
  } while (0)

enum { N = 6 };

static void grid(double* xyz, int32_t* tri) {
  int i, j, t = 0;
  for (j = 0; j <= N; ++j)
    for (i = 0; i <= N; ++i) {
      const double u = (double)i / N, v = (double)j / N;
      xyz[3 * (j * (N + 1) + i)] = u;
      xyz[3 * (j * (N + 1) + i) + 1] = v;
      xyz[3 * (j * (N + 1) + i) + 2] = 0.3 * sin(2 * u) * v;
    }
  for (j = 0; j < N; ++j)
    for (i = 0; i < N; ++i) {
      const int32_t a = j * (N + 1) + i, b = a + 1, c = a + N + 2, d = a + N + 1;
      tri[t++] = a; tri[t++] = b; tri[t++] = c;
      tri[t++] = a; tri[t++] = c; tri[t++] = d;
    }
}

static int cancel_on_second(void* user, double fraction, const char* stage) {
  int* calls = (int*)user;
  (void)fraction;
  (void)stage;
  return ++*calls >= 2;
}

int main(int argc, char** argv) {
  double xyz[3 * (N + 1) * (N + 1)];
  int32_t tri[6 * N * N];
  const int64_t nv = (N + 1) * (N + 1), nt = 2 * N * N;
  wefm_face* face = NULL;
  wefm_mesh* mesh = NULL;
  wefm_options opt;
  wefm_report rep;
  wefm_mesh_info info;
  int64_t count = 0, n = 0;
  double* uv;
  int32_t id = -1, solved = 0, calls = 0;
  char path[4096];
  if (argc != 3) {
    fprintf(stderr, "usage: %s MESH.obj OUTDIR\n", argv[0]);
    return 2;
  }
  grid(xyz, tri);
  EXPECT(strlen(wefm_version()) > 0);
  EXPECT(strcmp(wefm_status_string(WEFM_ERROR_SINGULAR), "WEFM_ERROR_SINGULAR") == 0);
  EXPECT(wefm_face_create(&face) == WEFM_OK);
  EXPECT(wefm_face_solve(face) == WEFM_ERROR_INVALID_STATE);

  /* bad meshes, then the good one */
  xyz[5] = NAN;
  EXPECT(wefm_face_set_mesh(face, nv, xyz, nt, tri) == WEFM_ERROR_INVALID_MESH);
  xyz[5] = 0;
  id = tri[4];
  tri[4] = -3;
  EXPECT(wefm_face_set_mesh(face, nv, xyz, nt, tri) == WEFM_ERROR_INVALID_MESH);
  tri[4] = id;
  EXPECT(wefm_face_set_mesh(face, nv, xyz, nt, tri) == WEFM_OK);

  wefm_options_init(&opt, sizeof opt);
  opt.s = 2.5;
  EXPECT(wefm_face_set_options(face, &opt) == WEFM_ERROR_INVALID_ARGUMENT);
  opt.s = 1;
  opt.max_rho_iterations = 5;
  EXPECT(wefm_face_set_options(face, &opt) == WEFM_OK);

  /* topology queries */
  EXPECT(wefm_face_edge_count(face, &n) == WEFM_OK && n == 1);
  EXPECT(wefm_face_loop_count(face, &n) == WEFM_OK && n == 1);
  EXPECT(wefm_face_get_loop_uses(face, 0, NULL, 0, &count) == WEFM_OK && count == 4 * N);
  EXPECT(wefm_face_use_count(face, &n) == WEFM_OK && n == nv);

  /* constraints */
  EXPECT(wefm_face_add_pin(face, 999, 0, 0, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  EXPECT(strstr(wefm_face_last_error(face), "999") != NULL);
  EXPECT(wefm_face_add_pin(face, 0, 0, 0, &id) == WEFM_OK);

  /* cancel through the callback, then a full solve */
  EXPECT(wefm_face_set_progress_callback(face, cancel_on_second, &calls) == WEFM_OK);
  EXPECT(wefm_face_solve(face) == WEFM_ERROR_CANCELLED);
  EXPECT(wefm_face_set_progress_callback(face, NULL, NULL) == WEFM_OK);
  {
    const wefm_status s = wefm_face_solve(face);
    EXPECT(s == WEFM_OK || s == WEFM_ERROR_NOT_CONVERGED);
  }
  EXPECT(wefm_face_has_result(face, &solved) == WEFM_OK && solved);
  EXPECT(wefm_face_get_uv(face, NULL, 0, &count) == WEFM_OK && count == 2 * nv);
  uv = (double*)malloc(sizeof(double) * (size_t)count);
  EXPECT(wefm_face_get_uv(face, uv, count - 1, &count) == WEFM_ERROR_BUFFER_TOO_SMALL);
  EXPECT(wefm_face_get_uv(face, uv, count, &count) == WEFM_OK);
  EXPECT(isfinite(uv[0]) && isfinite(uv[count - 1]));
  free(uv);
  wefm_report_init(&rep, sizeof rep);
  EXPECT(wefm_face_get_report(face, &rep) == WEFM_OK && rep.flipped_triangles == 0);
  EXPECT(wefm_face_get_step_history(face, NULL, 0, &count) == WEFM_OK);
  snprintf(path, sizeof path, "%s/capi_smoke_out.obj", argv[2]);
  EXPECT(wefm_face_write_obj(face, path) == WEFM_OK);
  EXPECT(wefm_face_retain(face) == WEFM_OK);
  wefm_face_release(face);

  /* meshes from a file and from arrays */
  EXPECT(wefm_mesh_read("/nonexistent/x.obj", 0, &mesh) == WEFM_ERROR_IO && mesh == NULL);
  EXPECT(wefm_mesh_read(argv[1], 0, &mesh) == WEFM_OK);
  wefm_mesh_info_init(&info, sizeof info);
  EXPECT(wefm_mesh_get_info(mesh, &info) == WEFM_OK && info.triangles > 0);
  EXPECT(wefm_face_set_mesh_from(face, mesh) == WEFM_OK);
  wefm_mesh_release(mesh);
  EXPECT(wefm_face_solve(face) == WEFM_OK);
  EXPECT(wefm_mesh_create(nv, xyz, nt, tri, &mesh) == WEFM_OK);
  EXPECT(wefm_mesh_get_vertices(mesh, NULL, 0, &count) == WEFM_OK && count == 3 * nv);
  wefm_mesh_release(mesh);

  wefm_face_release(face);
  wefm_face_release(NULL);
  EXPECT(wefm_face_solve(NULL) == WEFM_ERROR_NULL_ARGUMENT);
  if (failures) fprintf(stderr, "%d failures\n", failures);
  return failures ? 1 : 0;
}
