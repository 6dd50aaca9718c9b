# Generates granchain.1 and granchain-<command>.1 from the binary's own --help (help2man), so the
# pages cannot drift from the program. Called at install time with HELP2MAN, BINARY, OUT and
# INCLUDES (docs/man: one <page>.h2m per page with its EXAMPLES and SEE ALSO sections).
# A subcommand's page is made from a small wrapper named granchain-<command> that runs
# `granchain <command>`: help2man takes the page's title (.TH GRANCHAIN-RUN) and its NAME line
# (granchain-run \- ...) from the program's name.
file(MAKE_DIRECTORY "${OUT}")
# Each page's NAME line is the subcommand's one-line description in `granchain --help` (written
# once, in src/cli), its first letter lower-cased and its full stop dropped.
# The subcommands are those `granchain --help` lists.
execute_process(COMMAND "${BINARY}" --help OUTPUT_VARIABLE main_help)
string(REGEX REPLACE ".*\nSubcommands:\n" "" listed "${main_help}")
string(REGEX MATCHALL "(^|\n)  [a-z]+ " names "${listed}")
set(commands "")
foreach(n IN LISTS names)
  string(STRIP "${n}" n)
  list(APPEND commands "${n}")
endforeach()
if(NOT commands)
  message(FATAL_ERROR "granchain --help lists no subcommands")
endif()
foreach(c IN LISTS commands)
  if(NOT main_help MATCHES "\n  ${c} +([^\n]+)")
    message(FATAL_ERROR "granchain --help lists no subcommand ${c}")
  endif()
  string(REGEX REPLACE "\\.$" "" d "${CMAKE_MATCH_1}")
  string(SUBSTRING "${d}" 0 1 first)
  string(SUBSTRING "${d}" 1 -1 rest)
  string(TOLOWER "${first}" first)
  set(desc_${c} "${first}${rest}")
endforeach()
execute_process(COMMAND "${BINARY}" --version OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE)
string(REGEX REPLACE "\n.*" "" version "${version}")  # its first line: "granchain 0.1.0+g..."
string(REPLACE "granchain " "" version "${version}")
string(REGEX REPLACE "\\+.*" "" version "${version}")  # 0.1.0: the build's commit does not change the interface
execute_process(COMMAND ${HELP2MAN} --no-info --name "inelastic collapse in one-dimensional granular chains"
                        --version-string "${version}" --include "${INCLUDES}/granchain.h2m" --output "${OUT}/granchain.1"
                        "${BINARY}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man failed for granchain")
endif()
set(wrappers "${OUT}/.granchain-man-wrappers")
file(MAKE_DIRECTORY "${wrappers}")
foreach(c IN LISTS commands)
  file(WRITE "${wrappers}/granchain-${c}" "#!/bin/sh\nexec \"${BINARY}\" ${c} \"$@\"\n")
  file(CHMOD "${wrappers}/granchain-${c}" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE)
  execute_process(COMMAND ${HELP2MAN} --no-info --name "${desc_${c}}" --version-string "${version}"
                          --include "${INCLUDES}/granchain-${c}.h2m" --output "${OUT}/granchain-${c}.1"
                          "${wrappers}/granchain-${c}" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    file(REMOVE_RECURSE "${wrappers}")
    message(FATAL_ERROR "help2man failed for granchain ${c}")
  endif()
endforeach()
file(REMOVE_RECURSE "${wrappers}")
message(STATUS "granchain: man pages in ${OUT}")
