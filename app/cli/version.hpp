#pragma once
// What `grip --version` prints: grip's version, its git revision and the versions of the
// libraries it was built with.
#include <string>

namespace grip {

const char* git_revision();  // defined in the generated grip_revision.cpp
const char* version();       // e.g. "0.1.0"
std::string version_report();

}  // namespace grip
