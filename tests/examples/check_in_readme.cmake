# SPDX-License-Identifier: BSD-3-Clause
# Checks that a source file stands word for word in the README (inside a code block):
#   cmake -DREADME=<README.md> -DSOURCE=<file.cpp> -P check_in_readme.cmake
cmake_minimum_required(VERSION 3.20)
file(READ "${README}" readme)
file(READ "${SOURCE}" source)
string(FIND "${readme}" "```cpp\n${source}```" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${SOURCE} does not stand word for word in a ```cpp block of ${README}: copy it there again")
endif()
message(STATUS "ok: ${SOURCE} is in the README")
