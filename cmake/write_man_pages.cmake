# Generates granchain.1 and granchain-<command>.1 from the binary's own --help (help2man), so the
# pages cannot drift from the program. Called at install time with HELP2MAN, BINARY, OUT and
# INCLUDES (docs/man: one <page>.h2m per page with its EXAMPLES and SEE ALSO sections).
# A subcommand's page is made from a small wrapper named granchain-<command> that runs
# `granchain <command>`: help2man takes the page's title (.TH GRANCHAIN-RUN) and its NAME line
# (granchain-run \- ...) from the program's name.
file(MAKE_DIRECTORY "${OUT}")
set(commands run theory collapse sweep merge export analyze trace reproduce)
set(desc_run "run one driven column and measure its collision rate")
set(desc_theory "print the paper's closed forms")
set(desc_collapse "count collisions of free-space or wall collapses")
set(desc_sweep "run a grid of driven columns into a results store")
set(desc_merge "merge results stores")
set(desc_export "export a results store as CSV or JSON")
set(desc_analyze "analyse stored runs into the paper's regimes")
set(desc_trace "record and draw a space-time diagram")
set(desc_reproduce "reproduce the paper's figures and Table 1")
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
