#pragma once
// Starts the process again with glibc's malloc advising its memory for transparent huge pages
// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1), for the commands that solve. See the .cpp for why and
// when; returns (doing nothing) whenever a condition does not hold or exec fails.

namespace wefm_cli {

void reexec_with_huge_page_malloc(int argc, char** argv);

// Appends glibc.malloc.hugetlb=1 to this process's GLIBC_TUNABLES (for the programs it starts)
// unless the variable already names that tunable. Returns whether it changed the variable.
bool add_huge_page_malloc_tunable();

// Whether this process runs with glibc.malloc.hugetlb=1 (set here or by the caller).
bool huge_page_malloc_active();

}  // namespace wefm_cli
