#pragma once
// Which sparse factorisation solves the face's systems: an option of the method's settings, so it
// lives apart from the factorisation itself (options.hpp needs the choice, not the solver).

namespace wefm {

enum class Backend { Auto, Cholmod, Eigen };

}  // namespace wefm
