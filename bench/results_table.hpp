#pragma once
// Turns the benchmark's JSON results into the Markdown tables of docs/PERFORMANCE.md: per-stage
// times, multiples of the Laplacian floor, the CGAL ratio, peak memory and scaling exponents.
#include <string>

#include "case_runner.hpp"

namespace wefm_bench {

// `results` is the document wefm-bench writes (machine, command, cases, cli).
std::string markdown_tables(const Json& results);

// Fills results["exponents"]: log(t2/t1)/log(n2/n1) between consecutive sizes from 100k up.
void add_scaling_exponents(Json& results);

}  // namespace wefm_bench
