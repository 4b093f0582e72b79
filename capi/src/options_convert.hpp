#pragma once
#include "handles.hpp"

namespace wefm::capi {

wefm_options to_c(const wefm::Options& o);
wefm::Options from_c(const wefm_options& c);  // throws on values out of range

}  // namespace wefm::capi
