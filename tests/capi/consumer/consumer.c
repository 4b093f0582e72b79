/* A program as a mesher would write it, built against an *installed* wefm (tests/capi/consumer.cmake):
 * flatten two triangles and check the library that was loaded is the one the header describes. */
#include <stdio.h>
#include <string.h>

#include <wefm/wefm.h>

int main(void) {
  static const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  static const int32_t tri[] = {0, 1, 2, 0, 2, 3};
  wefm_face* face = NULL;
  double uv[8];
  int64_t count = 0;
  char expected[32];
  wefm_status st;

  snprintf(expected, sizeof expected, "%d.%d.%d", WEFM_VERSION_MAJOR, WEFM_VERSION_MINOR, WEFM_VERSION_PATCH);
  if (strcmp(wefm_version(), expected) != 0) {
    fprintf(stderr, "header %s but library %s\n", expected, wefm_version());
    return 1;
  }
  st = wefm_face_create(&face);
  if (st == WEFM_OK) st = wefm_face_set_mesh(face, 4, xyz, 2, tri);
  if (st == WEFM_OK) st = wefm_face_solve(face);
  if (st == WEFM_OK) st = wefm_face_get_uv(face, uv, 8, &count);
  if (st != WEFM_OK || count != 8) {
    fprintf(stderr, "flatten failed: %s: %s\n", wefm_status_string(st), face ? wefm_face_last_error(face) : wefm_last_error());
    wefm_face_release(face);
    return 1;
  }
  wefm_face_release(face);
  printf("consumer: wefm %s, %lld UV values\n", wefm_version(), (long long)count);
  return 0;
}
