#include "horizon/version.hpp"

namespace horizon {

const char* version() { return HORIZON_VERSION_STRING; }

}  // namespace horizon
