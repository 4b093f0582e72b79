/* Flatten a triangulated face from a mesh file and write it as OBJ with UVs, from C.
 *
 *   cc flatten_obj.c $(pkg-config --cflags --libs wefm) -Wl,-rpath,$(pkg-config --variable=libdir wefm)
 *   ./a.out IN.obj OUT.obj [S]
 *
 * Every call returns a wefm_status; the message of a failed call is wefm_face_last_error(face) for
 * calls on a face and wefm_last_error() for the others (reading a file has no face yet). */
#include <stdio.h>
#include <stdlib.h>

#include <wefm/wefm.h>

static int failed(const char* what, wefm_status st, const char* message) {
  fprintf(stderr, "%s: %s: %s\n", what, wefm_status_string(st), message);
  return 1;
}

int main(int argc, char** argv) {
  wefm_mesh* mesh = NULL;
  wefm_face* face = NULL;
  wefm_options options;
  wefm_report report;
  wefm_status st;
  int rc = 0;

  if (argc < 3) {
    fprintf(stderr, "usage: %s IN.obj OUT.obj [S]\n", argv[0]);
    return 2;
  }
  st = wefm_mesh_read(argv[1], 0.0, &mesh);
  if (st != WEFM_OK) return failed(argv[1], st, wefm_last_error());
  st = wefm_face_create(&face);
  if (st != WEFM_OK) {
    wefm_mesh_release(mesh);
    return failed("wefm_face_create", st, wefm_last_error());
  }
  wefm_options_init(&options, sizeof options); /* the defaults; then change what you need */
  if (argc > 3) options.s = atof(argv[3]);
  if ((st = wefm_face_set_options(face, &options)) != WEFM_OK ||
      (st = wefm_face_set_mesh_from(face, mesh)) != WEFM_OK)
    rc = failed(argv[1], st, wefm_face_last_error(face));
  /* NOT_CONVERGED still leaves the best layout reached: write it, and say so. */
  if (rc == 0 && (st = wefm_face_solve(face)) != WEFM_OK && st != WEFM_ERROR_NOT_CONVERGED)
    rc = failed("solve", st, wefm_face_last_error(face));
  if (rc == 0 && (st = wefm_face_write_obj(face, argv[2])) != WEFM_OK)
    rc = failed(argv[2], st, wefm_face_last_error(face));
  if (rc == 0) {
    wefm_report_init(&report, sizeof report);
    wefm_face_get_report(face, &report);
    printf("wrote %s: score %.6f, angle distortion max %.6f, %lld flipped triangle(s)%s\n", argv[2], report.score,
           report.angle_distortion_max, (long long)report.flipped_triangles, report.converged ? "" : " (not converged)");
  }
  wefm_face_release(face);
  wefm_mesh_release(mesh);
  return rc;
}
