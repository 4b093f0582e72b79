#pragma once
// Flattening one face from files to files: the pipeline `wefm flatten` runs once and `wefm batch`
// runs per face on worker threads (each job owns its handles, so jobs share nothing).
#include <string>
#include <utility>
#include <vector>

#include "face_snapshot.hpp"
#include "flatten_settings.hpp"
#include "progress.hpp"

namespace wefm_cli {

struct FaceJob {
  std::string input;            // mesh file
  std::string output_mesh;      // UV mesh to write, format by extension (mesh_formats.hpp; "" = none)
  int face_tag = 1;             // its face group (MSH physical group "face_<tag>", cell data face_id)
  FlattenSettings settings;     // options and the optional side files
  bool show_progress = false;
  std::string progress_prefix;  // batch: the face name
  CancelWatcher* watcher = nullptr;
};

struct Timings {
  double read = 0, setup = 0, solve = 0, write = 0, total = 0;  // wall seconds seen by the tool
};

struct FaceOutcome {
  int exit_code = 0;                 // see exit_codes.hpp
  std::string error;                 // what failed, naming the file ("" on success)
  std::vector<std::string> warnings;
  std::vector<std::pair<std::string, std::string>> outputs;  // (what, path) written
  bool topology_built = false;
  FaceSnapshot snap;
  Timings time;
};

FaceOutcome run_face_job(const FaceJob& job);

}  // namespace wefm_cli
