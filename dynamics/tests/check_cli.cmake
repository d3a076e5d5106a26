# Runs one `rockcontact` command line and checks what scripts calling it rely on: the exit
# status, regular expressions on stdout and stderr, and that the JSON it writes parses (with,
# optionally, the status of every result in order).
#
#   cmake -DEXE=path/to/rockcontact -DEXPECT_EXIT=0 -DARGC=n -DARG0=pairs -DARG1=in.json ...
#         [-DSTDOUT_REGEX=re] [-DSTDERR_REGEX=re] [-DJSON_FILE=out.json | -DJSON_STDOUT=ON]
#         [-DEXPECT_STATUSES=overlap,touch,...] -P check_cli.cmake
cmake_minimum_required(VERSION 3.25)

foreach(required EXE EXPECT_EXIT ARG_COUNT)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "check_cli.cmake: -D${required}=... is required")
  endif()
endforeach()

set(args "")
if(ARG_COUNT GREATER 0)
  math(EXPR last "${ARG_COUNT} - 1")
  foreach(i RANGE ${last})
    list(APPEND args "${ARG${i}}")
  endforeach()
endif()

if(JSON_FILE)
  file(REMOVE "${JSON_FILE}")  # a stale file from an earlier run must not pass the check
endif()

execute_process(COMMAND "${EXE}" ${args}
  RESULT_VARIABLE exit_status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(JOIN " " command_line "${EXE}" ${args})
set(report "command: ${command_line}\nexit status: ${exit_status}\n--- stdout\n${out}--- stderr\n${err}")

if(NOT exit_status STREQUAL EXPECT_EXIT)
  message(FATAL_ERROR "expected exit status ${EXPECT_EXIT}\n${report}")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  message(FATAL_ERROR "stdout does not match '${STDOUT_REGEX}'\n${report}")
endif()
if(DEFINED STDERR_REGEX AND NOT err MATCHES "${STDERR_REGEX}")
  message(FATAL_ERROR "stderr does not match '${STDERR_REGEX}'\n${report}")
endif()

if(JSON_FILE)
  if(NOT EXISTS "${JSON_FILE}")
    message(FATAL_ERROR "no JSON written to ${JSON_FILE}\n${report}")
  endif()
  file(READ "${JSON_FILE}" document)
elseif(JSON_STDOUT)
  set(document "${out}")
else()
  return()
endif()

string(JSON result_count ERROR_VARIABLE json_error LENGTH "${document}" results)
if(json_error)
  message(FATAL_ERROR "the JSON output does not parse or has no results: ${json_error}\n${report}")
endif()
if(DEFINED EXPECT_STATUSES)
  set(statuses "")
  if(result_count GREATER 0)
    math(EXPR last "${result_count} - 1")
    foreach(i RANGE ${last})
      string(JSON status GET "${document}" results ${i} status)
      list(APPEND statuses "${status}")
    endforeach()
  endif()
  string(REPLACE "," ";" expected_statuses "${EXPECT_STATUSES}")
  if(NOT statuses STREQUAL expected_statuses)
    message(FATAL_ERROR "statuses ${statuses}, expected ${expected_statuses}\n${report}")
  endif()
endif()
