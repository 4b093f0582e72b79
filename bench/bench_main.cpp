// wefm-bench: timings per stage, peak memory, the Laplacian floor and the CGAL peer for scaling
// faces, as JSON and Markdown. See docs/PERFORMANCE.md for what the columns mean.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "case_runner.hpp"
#include "child_process.hpp"
#include "huge_page_malloc.hpp"
#include "process_policy.hpp"
#include "process_stats.hpp"
#include "results_table.hpp"
#include "wefm/wefm.h"

using namespace wefm_bench;

namespace {

const char* kUsage =
    "usage: wefm-bench [options]                 run the benchmark (each case in a fresh process)\n"
    "       wefm-bench --generate SHAPE SIZE -o FILE.obj   write a benchmark face (and FILE.seam for the tube)\n"
    "       wefm-bench --table-from A.json[,B.json...] [--json FILE] [--markdown FILE]   merge earlier results\n"
    "\n"
    "  --shapes LIST     disk,plate,tube (default disk,plate; tube has a seam, given to wefm)\n"
    "  --sizes LIST      triangle counts, e.g. 10k,100k,1M (default 10k,100k,1M)\n"
    "  --4m              add the 4M size\n"
    "  --s LIST          roll-out exponents (default 0,1,2)\n"
    "  --timeout SEC     per case; a case over it is killed and reported as timed out (default 1200)\n"
    "  --threads N       wefm_options.threads of the library cases; the whole-process run passes it to\n"
    "                    `wefm flatten --threads` (default: the machine's hardware threads, as the tool)\n"
    "  --cli PATH|none   wefm executable for the whole-process run (default: the build tree's apps/wefm)\n"
    "  --cli-s LIST      s values of the whole-process run (default 0), at the largest size\n"
    "  --cgal PATH|none  CGAL peer executable (default: wefm-bench-cgal next to this program, if built)\n"
    "  --no-floor        skip the Laplacian floor;  --no-io: skip the file reading/writing case\n"
    "  --work DIR        scratch directory for OBJ files (default /tmp)\n"
    "  --json FILE       results (default bench-results.json);  --markdown FILE (default bench-results.md)\n";

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "wefm-bench: %s\n\n%s", msg.c_str(), kUsage);
  std::exit(2);
}

Shape shape_arg(const std::string& s) {
  Shape shape;
  if (!parse_shape(s, shape)) usage_error("unknown shape '" + s + "' (disk, plate, tube)");
  return shape;
}

int64_t size_arg(const std::string& s) {
  int64_t n;
  if (!parse_size(s, n)) usage_error("bad size '" + s + "' (e.g. 10k, 1M, 250000)");
  return n;
}

double number_arg(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end) usage_error("bad number '" + s + "'");
  return v;
}

bool executable(const std::string& path) { return !path.empty() && access(path.c_str(), X_OK) == 0; }

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return b;
}

// The child side: one case, its JSON on stdout.
int run_case(const std::vector<std::string>& a) {
  if (a.size() < 3) usage_error("--case KIND SHAPE SIZE ...");
  const Shape shape = shape_arg(a[1]);
  const int64_t size = size_arg(a[2]);
  Json j;
  // The library's cases run under the policy the wefm tool chooses for itself (OpenBLAS at one
  // thread, huge-page advice; wefm.h "Process."), so their times compare with the tool's and with
  // earlier tables; OPENBLAS_NUM_THREADS or WEFM_HUGE_PAGES=0 in the environment measure the
  // library's hands-off default instead.
  if (a[0] == "wefm") wefm_cli::opt_in_process_policy();
  if (a[0] == "wefm" && a.size() == 5) j = run_wefm_case(shape, size, number_arg(a[3]), static_cast<int>(number_arg(a[4])));
  else if (a[0] == "floor") j = run_floor_case(shape, size, false);
  else if (a[0] == "floor_complex") j = run_floor_case(shape, size, true);
  else if (a[0] == "io" && a.size() == 4) j = run_io_case(shape, size, a[3]);
  else usage_error("unknown case '" + a[0] + "'");
  std::printf("%s\n", j.dump().c_str());
  return 0;
}

struct Settings {
  std::vector<Shape> shapes{Shape::BumpyDisk, Shape::HoledPlate};
  std::vector<int64_t> sizes{10000, 100000, 1000000};
  std::vector<double> s{0, 1, 2};
  std::vector<double> cli_s{0};
  double timeout = 1200;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string cli, cgal, work = "/tmp", json = "bench-results.json", markdown = "bench-results.md";
  bool floor = true, io = true;
};

void save(const Json& results, const Settings& st) {
  std::ofstream(st.json) << results.dump(1) << "\n";
  std::ofstream(st.markdown) << markdown_tables(results);
}

// Runs a child case and turns what it printed (or how it died) into the case's JSON.
Json child_case(const std::vector<std::string>& argv, const Settings& st, Json header) {
  const ChildResult r = run_child(argv, st.timeout);
  Json j = header;
  if (r.exit_code == 0 && !r.timed_out) {
    try {
      // The case's JSON is the last line; anything before it is stray output.
      const auto start = r.out.rfind("\n{", r.out.size() > 1 ? r.out.size() - 2 : 0);
      j = Json::parse(r.out.substr(start == std::string::npos ? 0 : start + 1));
    } catch (const std::exception& e) {
      j["error"] = std::string("unreadable case output: ") + e.what();
    }
  } else {
    j["timed_out"] = r.timed_out;
    j["error"] = r.timed_out ? "timed out" : r.signal ? "killed by signal " + std::to_string(r.signal) : "exit code " + std::to_string(r.exit_code);
  }
  j["wall"] = r.wall;
  j["cpu_user"] = r.user;
  j["cpu_sys"] = r.sys;
  j["max_rss_mb"] = r.max_rss_mb;
  return j;
}

// `wefm flatten` on an OBJ written by the generator: the whole job a user runs.
Json cli_case(const Settings& st, Shape shape, int64_t size, double s) {
  Json j{{"shape", shape_name(shape)}, {"size", size_label(size)}, {"s", s}};
  const std::string base = st.work + "/wefm-bench-" + std::to_string(getpid()) + "-" + shape_name(shape) + "_" + size_label(size);
  bool seams = false;
  {
    const Face f = generate(shape, size);
    j["triangles"] = f.triangles();
    if (!write_obj(base + ".obj", f) || (!f.seam.empty() && !write_seam(base + ".seam", f))) {
      j["status"] = "cannot write " + base + ".obj";
      return j;
    }
    seams = !f.seam.empty();
  }
  char sbuf[32];
  std::snprintf(sbuf, sizeof sbuf, "%g", s);
  std::vector<std::string> argv{st.cli, "flatten", base + ".obj", "-o", base + "_uv.obj", "--s", sbuf, "--quiet", "--report", base + ".json",
                                "--threads", std::to_string(st.threads)};
  if (seams) argv.insert(argv.end(), {"--seams", base + ".seam"});
  const ChildResult r = run_child(argv, st.timeout);
  j["wall"] = r.wall;
  j["cpu_user"] = r.user;
  j["cpu_sys"] = r.sys;
  j["max_rss_mb"] = r.max_rss_mb;
  j["exit_code"] = r.exit_code;
  j["status"] = r.timed_out ? "timed out" : r.exit_code == 0 ? "ok" : "exit code " + std::to_string(r.exit_code);
  try {
    std::ifstream in(base + ".json");
    const Json rep = Json::parse(in);
    for (const char* k : {"read_input", "setup", "wall_solve", "wall_before_report"}) j[k] = rep["timings"][k];
    j["report_timings"] = rep["timings"];
  } catch (const std::exception&) {
  }
  for (const char* ext : {".obj", ".seam", "_uv.obj", ".json"}) std::remove((base + ext).c_str());
  return j;
}

int run_benchmark(const Settings& st, const std::string& command) {
  Json results;
  results["command"] = command;
  results["date"] = utc_now();
  results["wefm_version"] = wefm_version();
  results["suitesparse"] = wefm_has_suitesparse() != 0;
  results["machine"] = machine_description();
  // Every case (wefm in-process, the floor, the CGAL peer, the whole-process wefm) runs with
  // glibc's huge-page malloc, as the wefm tool runs itself (apps/README.md, "Environment"): the
  // same allocator for all, and the library measured as the tool and a tuned host run it. A
  // caller's own setting of the tunable is kept (glibc.malloc.hugetlb=0 measures without).
  wefm_cli::add_huge_page_malloc_tunable();
  results["glibc_tunables"] = std::getenv("GLIBC_TUNABLES");
  results["threads"] = st.threads;
  results["load_start"] = load_average();
  results["timeout"] = st.timeout;
  results["cases"] = Json::array();
  results["cli"] = Json::array();
  const std::string self = executable_dir() + "wefm-bench";
  std::fprintf(stderr, "wefm-bench: %s\n  CGAL peer: %s; whole-process: %s\n", results["machine"].get<std::string>().c_str(),
               st.cgal.empty() ? "off (--cgal none, or not built: apt-get install libcgal-dev and rebuild)" : st.cgal.c_str(), st.cli.empty() ? "no" : st.cli.c_str());
  auto run = [&](const std::vector<std::string>& argv, Json header) {
    std::string what;
    for (size_t k = 1; k < argv.size(); ++k) what += (k > 1 ? " " : "") + argv[k];
    std::fprintf(stderr, "  %-40s", what.c_str());
    const double load = load_average();
    Json j = child_case(argv, st, header);
    j["load_before"] = load;
    std::fprintf(stderr, " %8.2f s  %6.0f MB  %s\n", j["wall"].get<double>(), j["max_rss_mb"].get<double>(),
                 j.value("status", j.value("error", "")).c_str());
    results["cases"].push_back(j);
    save(results, st);
  };
  for (Shape shape : st.shapes)
    for (int64_t size : st.sizes) {
      const std::string sh = shape_name(shape), sz = size_label(size);
      // What a case that dies before printing is recorded as.
      auto header = [&](const char* kind) { return Json{{"kind", kind}, {"shape", sh}, {"size", sz}}; };
      if (st.floor) {
        run({self, "--case", "floor", sh, sz}, header("floor"));
        run({self, "--case", "floor_complex", sh, sz}, header("floor_complex"));
      }
      if (st.io) run({self, "--case", "io", sh, sz, st.work}, header("io"));
      if (!st.cgal.empty()) run({st.cgal, "--case", sh, sz}, header("cgal"));
      for (double s : st.s) {
        char sbuf[32];
        std::snprintf(sbuf, sizeof sbuf, "%g", s);
        Json h = header("wefm");
        h["s"] = s;
        run({self, "--case", "wefm", sh, sz, sbuf, std::to_string(st.threads)}, h);
      }
    }
  if (!st.cli.empty())
    for (Shape shape : st.shapes)
      for (double s : st.cli_s) {
        std::fprintf(stderr, "  wefm flatten %s %s s=%g", shape_name(shape), size_label(st.sizes.back()).c_str(), s);
        Json j = cli_case(st, shape, st.sizes.back(), s);
        std::fprintf(stderr, " %8.2f s  %6.0f MB  %s\n", j.value("wall", 0.0), j.value("max_rss_mb", 0.0), j.value("status", "").c_str());
        results["cli"].push_back(j);
        save(results, st);
      }
  results["load_end"] = load_average();
  add_scaling_exponents(results);
  save(results, st);
  std::fprintf(stderr, "wrote %s and %s\n", st.json.c_str(), st.markdown.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);
  if (!a.empty() && a[0] == "--case") return run_case({a.begin() + 1, a.end()});
  Settings st;
  std::string cli = "auto", cgal = "auto", table_from, generate_out;
  std::vector<std::string> generate_args;
  std::string command = "wefm-bench";
  for (const auto& x : a) command += " " + x;
  for (size_t k = 0; k < a.size(); ++k) {
    auto value = [&]() -> const std::string& {
      if (k + 1 >= a.size()) usage_error(a[k] + " needs a value");
      return a[++k];
    };
    const std::string& o = a[k];
    if (o == "--help" || o == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (o == "--generate") {
      const std::string& shape = value();
      generate_args = {shape, value()};
    } else if (o == "-o") generate_out = value();
    else if (o == "--table-from") table_from = value();
    else if (o == "--shapes") {
      st.shapes.clear();
      for (const auto& s : split(value())) st.shapes.push_back(shape_arg(s));
    } else if (o == "--sizes") {
      st.sizes.clear();
      for (const auto& s : split(value())) st.sizes.push_back(size_arg(s));
    } else if (o == "--4m") st.sizes.push_back(4000000);
    else if (o == "--s") {
      st.s.clear();
      for (const auto& s : split(value())) st.s.push_back(number_arg(s));
    } else if (o == "--cli-s") {
      st.cli_s.clear();
      for (const auto& s : split(value())) st.cli_s.push_back(number_arg(s));
    } else if (o == "--timeout") st.timeout = number_arg(value());
    else if (o == "--threads") st.threads = static_cast<int>(number_arg(value()));
    else if (o == "--cli") cli = value();
    else if (o == "--cgal") cgal = value();
    else if (o == "--no-floor") st.floor = false;
    else if (o == "--no-io") st.io = false;
    else if (o == "--work") st.work = value();
    else if (o == "--json") st.json = value();
    else if (o == "--markdown") st.markdown = value();
    else usage_error("unknown option '" + o + "'");
  }
  if (!generate_args.empty()) {
    if (generate_out.empty()) usage_error("--generate needs -o FILE.obj");
    const Face f = generate(shape_arg(generate_args[0]), size_arg(generate_args[1]));
    if (!write_obj(generate_out, f)) {
      std::fprintf(stderr, "wefm-bench: cannot write %s: %s\n", generate_out.c_str(), std::strerror(errno));
      return 1;
    }
    std::fprintf(stderr, "%s: %lld vertices, %lld triangles\n", generate_out.c_str(), static_cast<long long>(f.vertices()),
                 static_cast<long long>(f.triangles()));
    if (!f.seam.empty()) {
      // FILE.seam next to FILE.obj, for `wefm flatten FILE.obj --seams FILE.seam`.
      const size_t dot = generate_out.rfind('.');
      const std::string seam = (dot == std::string::npos || generate_out.find('/', dot) != std::string::npos ? generate_out : generate_out.substr(0, dot)) + ".seam";
      if (!write_seam(seam, f)) {
        std::fprintf(stderr, "wefm-bench: cannot write %s: %s\n", seam.c_str(), std::strerror(errno));
        return 1;
      }
      std::fprintf(stderr, "%s: %lld facet edges of the seam\n", seam.c_str(), static_cast<long long>(f.seam.size() / 2));
    }
    return 0;
  }
  if (!table_from.empty()) {
    // Several result files (comma-separated) merge into one table; a case run again in a later
    // file replaces the earlier one, so a slow case can be re-measured alone.
    Json results;
    for (const std::string& file : split(table_from)) {
      std::ifstream in(file);
      if (!in) usage_error("cannot read " + file);
      Json part = Json::parse(in);
      if (results.is_null()) {
        results = part;
        continue;
      }
      results["command"] = results.value("command", "") + "` and `" + part.value("command", "");
      results["date"] = results.value("date", "") + " and " + part.value("date", "");
      results["load_end"] = part["load_end"];
      for (const char* list : {"cases", "cli"})
        for (const Json& c : part[list]) {
          Json& all = results[list];
          for (size_t k = 0; k < all.size(); ++k)
            if (all[k].value("kind", "") == c.value("kind", "") && all[k].value("shape", "") == c.value("shape", "") &&
                all[k].value("size", "") == c.value("size", "") && all[k].value("s", -1.0) == c.value("s", -1.0)) {
              all.erase(k);
              break;
            }
          all.push_back(c);
        }
    }
    for (const char* list : {"cases", "cli"}) {
      Json& all = results[list];
      auto nominal = [](const Json& c) {  // a case that died has no triangle count, but its size label
        int64_t n = 0;
        return parse_size(c.value("size", ""), n) ? n : int64_t{0};
      };
      std::stable_sort(all.begin(), all.end(), [&](const Json& a, const Json& b) {
        return std::make_tuple(a.value("shape", ""), nominal(a), a.value("s", -1.0)) <
               std::make_tuple(b.value("shape", ""), nominal(b), b.value("s", -1.0));
      });
    }
    add_scaling_exponents(results);
    std::ofstream(st.markdown) << markdown_tables(results);
    std::ofstream(st.json) << results.dump(1) << "\n";
    return 0;
  }
  const std::string dir = executable_dir();
  st.cli = cli == "none" ? "" : cli == "auto" ? (executable(dir + "../apps/wefm") ? dir + "../apps/wefm" : "") : cli;
  st.cgal = cgal == "none" ? "" : cgal == "auto" ? (executable(dir + "wefm-bench-cgal") ? dir + "wefm-bench-cgal" : "") : cgal;
  if (!st.cli.empty() && !executable(st.cli)) usage_error("--cli: " + st.cli + " is not an executable");
  if (!st.cgal.empty() && !executable(st.cgal)) usage_error("--cgal: " + st.cgal + " is not an executable");
  // The scratch directory is made now: a missing one used to fail only the file cases, minutes in.
  std::error_code ec;
  std::filesystem::create_directories(st.work, ec);
  if (ec || !std::filesystem::is_directory(st.work)) usage_error("--work: cannot make the directory " + st.work + (ec ? ": " + ec.message() : ""));
  return run_benchmark(st, command);
}
