# SPDX-License-Identifier: BSD-3-Clause
# Runs one example with a command line and checks how it ends:
#   cmake -DCOMMAND=<program;arg;...> -DEXPECT_CODE=<n> -DEXPECT=<regex> [-DONE_LINE=ON] -P check_command_line.cmake
# EXPECT must match what the program printed (stdout and stderr together); with ONE_LINE the
# program must print exactly one line on stderr (a bad command line is one clear line).
cmake_minimum_required(VERSION 3.20)
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
set(printed "${out}${err}")
if(NOT code STREQUAL "${EXPECT_CODE}")
  message(FATAL_ERROR "exit code ${code}, expected ${EXPECT_CODE}; it printed:\n${printed}")
endif()
if(NOT printed MATCHES "${EXPECT}")
  message(FATAL_ERROR "the output does not match '${EXPECT}':\n${printed}")
endif()
if(ONE_LINE)
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines count)
  if(NOT count EQUAL 1 OR NOT out STREQUAL "")
    message(FATAL_ERROR "expected one line on stderr and nothing on stdout, got:\n${printed}")
  endif()
endif()
message(STATUS "ok: exit code ${code}, matched '${EXPECT}'")
