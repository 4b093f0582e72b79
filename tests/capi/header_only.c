/* Compiled by ctest (capi.header_c99, capi.header_cxx*) with -Werror: wefm.h must stand alone, in C99 and
 * in C++, included twice, and use every type it declares without warnings. The C++ build also uses
 * the one-argument *_init overloads. */
#include <wefm/wefm.h>
#include <wefm/wefm.h>

int main(void) {
  wefm_options options;
  wefm_report report;
  wefm_mesh_info info;
  wefm_mesh_options mesh_options;
  wefm_mesh_report mesh_report;
  wefm_progress_fn progress = 0;
  wefm_face* face = 0;
  wefm_mesh* mesh = 0;
  wefm_domain_mesh* domain = 0;
  wefm_status status = WEFM_OK;
  int enums = WEFM_METHOD_GLOBAL + WEFM_EDGE_AUTO + WEFM_SOLVER_AUTO + WEFM_MESH_FREE;
#ifdef __cplusplus
  status = wefm_options_init(&options);
#else
  status = wefm_options_init(&options, sizeof options);
#endif
  (void)report; (void)info; (void)mesh_options; (void)mesh_report; (void)progress;
  (void)face; (void)mesh; (void)domain;
  return status == WEFM_OK && WEFM_VERSION_NUMBER >= 0 ? enums : 1;
}
