# Shared by the generator's negative controls (included by the scripts run with -P).

# The method blocks of the spec file `spec` into `out` (a CMake list; the spec's own ';' are
# kept as <semicolon>: `diagonal` lists are not CMake list separators).
function(spec_blocks spec out)
  file(READ ${spec} text)
  string(REPLACE ";" "<semicolon>" text "${text}")
  string(REGEX MATCHALL "\nmethod[ \t]+[^\n]*\n([^m\n][^\n]*\n|modified[^\n]*\n)*" blocks "\n${text}")
  list(LENGTH blocks n)
  if(n EQUAL 0)
    message(FATAL_ERROR "no method blocks found in ${spec}")
  endif()
  set(${out} "${blocks}" PARENT_SCOPE)
endfunction()

# The `method` name of a block into `out`, and the name as a regular expression into `out`_re.
function(block_name block out)
  string(REGEX MATCH "method[ \t]+([^\n]*)" _ "${block}")
  string(REGEX REPLACE "([][()+.*^$?|\\\\])" "\\\\\\1" name_re "${CMAKE_MATCH_1}")
  set(${out} "${CMAKE_MATCH_1}" PARENT_SCOPE)
  set(${out}_re "${name_re}" PARENT_SCOPE)
endfunction()

# Runs the generator on the spec text `block` (in WORKDIR/file) and fails unless it refuses with
# an error matching `expected`; the error into `out`.
function(expect_refusal block file expected what out)
  string(REPLACE "<semicolon>" ";" block "${block}")
  file(WRITE ${WORKDIR}/${file} "${block}")
  file(MAKE_DIRECTORY ${WORKDIR}/out/include/erkn/generated ${WORKDIR}/out/src)
  execute_process(COMMAND ${GENERATOR} ${WORKDIR}/${file} ${WORKDIR}/out
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(rc EQUAL 0 OR NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${what}: expected a refusal naming it and a tree, got exit ${rc}: ${err}")
  endif()
  message(STATUS "refused as expected: ${err}")
  set(${out} "${err}" PARENT_SCOPE)
endfunction()
