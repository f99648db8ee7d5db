#pragma once
// Where a program named in a config would be run from, as execvp would find it (PATH), so that
// a missing one is reported with the package to install before anything is forked.
#include <string>

namespace rlrun {

// `binary` itself when it contains a '/' and is executable; else the first executable
// PATH/binary; "" when there is none.
std::string find_executable(const std::string& binary);

}  // namespace rlrun
