#pragma once
// Where rlrun's shipped data is at run time: configs/ (with configs/zoo and configs/sweeps),
// scenarios/ (grasp and traffic scenario files) and sumo_data/ (the SUMO networks the traffic
// scenarios name). No path is compiled into the binary, so an install can be moved as a whole
// (`cmake --install build --prefix P`, then `mv P Q`). The places searched, in this order:
//
//   1. $RLRUN_DATA_DIR (ProcessSettings::data_dir), when not empty: the user's override (a relocated or edited copy
//      of the data). It must hold scenarios/, else rlrun stops with an error naming it; it is
//      never silently skipped.
//   2. <dir>/../share/rlrun: an install (P/bin/rlrun reads P/share/rlrun; CMake's
//      CMAKE_INSTALL_BINDIR and CMAKE_INSTALL_DATADIR set the two names).
//   3. <dir>/share/rlrun: a build tree (build/rlrun reads build/share/rlrun, which CMake fills
//      with links to the source tree's configs/, scenarios/ and sumo_data/) and the Python
//      package (build/python/rlrun/share/rlrun, and the same inside an installed wheel).
//   4. <dir>/../share/rlrun, for a build tree's build/tests/rlrun_tests (the same as 2 unless
//      the install directories were changed).
//
// <dir> is the directory of the file holding this code: the rlrun executable, the test binary,
// or the shared object it is linked into (the Python extension module, a library), as the
// kernel maps it (symbolic links resolved). A candidate counts when it has a scenarios/
// directory.
#include <filesystem>
#include <optional>
#include <string>

namespace rlrun {

// The directory of the executable or shared object this code was linked into (absolute,
// links resolved). Throws RuntimeFailure if /proc/self/maps cannot tell (no /proc).
std::filesystem::path running_binary_dir();

// The shipped data directory (absolute), or nullopt when no candidate above has scenarios/.
// Throws RuntimeFailure when RLRUN_DATA_DIR is set to a directory without scenarios/.
std::optional<std::filesystem::path> find_shipped_data_dir();

// The shipped data directory; throws RuntimeFailure naming every place searched and
// RLRUN_DATA_DIR when there is none.
std::string shipped_data_dir();

// A data file a user or config names: `path` when it exists from the working directory; else,
// for a relative path, the same path inside the shipped data directory when it exists there
// (so `scenarios/grasp/lift.yaml` works from any directory); else `path` unchanged (the caller
// reports it missing).
std::string find_data_file(const std::string& path);

}  // namespace rlrun
