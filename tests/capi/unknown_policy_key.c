/* An unknown process-policy key as a C caller passes it. A C enum holds any int; in C++ the value
 * 77 lies outside wefm_process_policy's range, so the C++ test makes it here. */
#include <wefm/wefm.h>

wefm_status set_unknown_policy_key(int64_t value) { return wefm_set_process_policy((wefm_process_policy)77, value); }
wefm_status get_unknown_policy_key(int64_t* value) { return wefm_get_process_policy((wefm_process_policy)77, value); }
