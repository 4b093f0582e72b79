#pragma once
// SVG text pieces shared by the domain picture and the model atlas.
#include <cstdio>
#include <string>

#include "domain_picture.hpp"
#include "text_out.hpp"

namespace wefm_cli {

// "#rrggbb"
inline void put_hex(TextOut& out, const Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  out.put(buf);
}

// XML text or attribute value with &, <, > and " escaped.
inline void put_escaped(TextOut& out, const std::string& s) {
  for (char c : s) {
    switch (c) {
      case '&': out.put("&amp;"); break;
      case '<': out.put("&lt;"); break;
      case '>': out.put("&gt;"); break;
      case '"': out.put("&quot;"); break;
      default: out.put(c);
    }
  }
}

}  // namespace wefm_cli
