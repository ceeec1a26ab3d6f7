# Writes OUT, a C++ file whose masav::app::build_info::git() returns `git describe --always
# --dirty --tags` of SOURCE_DIR ("unknown" outside a git checkout). Run at every build (the
# custom target masav_git_describe, app/CMakeLists.txt), so the version a binary reports is the
# commit it was built from, not the one its build directory was configured at; the file is
# rewritten only when the text changes, so an unchanged tree rebuilds nothing.
#   cmake -DSOURCE_DIR=<repo> -DOUT=<file.cpp> -P cmake/git_describe.cmake
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0 OR NOT describe MATCHES "^[A-Za-z0-9._+-]+$")
  set(describe "unknown")
endif()
set(text "// Generated at build time by cmake/git_describe.cmake.
#include \"app/build_info.h\"

namespace masav::app::build_info {
const char* git() { return \"${describe}\"; }
}  // namespace masav::app::build_info
")
set(old "")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
