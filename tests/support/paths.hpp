#pragma once
// Where the tests find the `pba` program and the source tree. Defined in a file the build writes
// (tests/support/paths.cpp.in), so that no other test file's compilation depends on where the
// checkout lies and a compiler cache can serve them from one clone to the next.
#include <filesystem>
#include <string>

namespace pba::test {

std::string pbaBinary();
std::filesystem::path sourceDir();

} // namespace pba::test
