#include "obj_output.hpp"

#include "exit_codes.hpp"
#include "text_out.hpp"
#include "wefm/wefm.h"

namespace wefm_cli {

int write_uv_obj(const std::string& path, const std::string& input, const FaceSnapshot& snap, std::string& error) {
  TextOut out;
  if (!out.open(path)) {
    error = out.error();
    return out.failure_code();
  }
  out.put("# wefm ");
  out.put(wefm_version());
  out.put(" flatten of ");
  // A newline in a file name would end the comment and corrupt the OBJ.
  for (char c : input) out.put(c == '\n' || c == '\r' ? ' ' : c);
  out.put("\n# v: 3D vertices in input order; vt: UV per vertex use; f: vertex/use (1-based)\n");
  const size_t nv = snap.xyz.size() / 3;
  for (size_t i = 0; i < nv; ++i) {
    out.put("v ");
    out.num(snap.xyz[3 * i]);
    out.put(' ');
    out.num(snap.xyz[3 * i + 1]);
    out.put(' ');
    out.num(snap.xyz[3 * i + 2]);
    out.put('\n');
  }
  const size_t nu = snap.uv.size() / 2;
  for (size_t i = 0; i < nu; ++i) {
    out.put("vt ");
    out.num(snap.uv[2 * i]);
    out.put(' ');
    out.num(snap.uv[2 * i + 1]);
    out.put('\n');
  }
  const size_t nt = snap.tris.size() / 3;
  const bool have_uses = snap.tri_uses.size() == snap.tris.size();
  for (size_t t = 0; t < nt; ++t) {
    out.put('f');
    for (int c = 0; c < 3; ++c) {
      out.put(' ');
      out.integer(int64_t{snap.tris[3 * t + c]} + 1);
      out.put('/');
      out.integer(int64_t{have_uses ? snap.tri_uses[3 * t + c] : snap.tris[3 * t + c]} + 1);
    }
    out.put('\n');
  }
  if (!out.close()) {
    error = out.error();
    return out.failure_code();
  }
  return kExitOk;
}

}  // namespace wefm_cli
