// The library's version, compiled in from the generated header.
#include "clothcd/version.hpp"

namespace clothcd {

const char* version() { return kVersionString; }

}  // namespace clothcd
