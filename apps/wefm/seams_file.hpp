#pragma once
// The seam file format of /work/shared/data (and face.seam): one facet edge per line as two 0-based
// vertex indices; '#' starts a comment; blank lines are ignored.
#include <cstdint>
#include <string>
#include <vector>

namespace wefm_cli {

// Appends 2 indices per facet edge to `pairs`. On failure returns an exit code (3 unreadable,
// 4 malformed) and a message naming the file and line; returns 0 on success.
int read_seams_file(const std::string& path, std::vector<int32_t>& pairs, std::string& error);

// True when the file has at least one non-comment, non-blank line (face.seam files of faces without
// seams hold comments only; batch uses this to skip them).
bool seams_file_has_data(const std::string& path);

}  // namespace wefm_cli
