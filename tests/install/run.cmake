# run(<command> <args>...): runs the command and stops the script with its output if it exits
# non-zero; sets `out` to its standard output in the caller. It runs in RUN_DIRECTORY if the
# including script sets that variable, else in the current directory.
function(run)
  if(RUN_DIRECTORY)
    set(directory WORKING_DIRECTORY ${RUN_DIRECTORY})
  endif()
  execute_process(COMMAND ${ARGV} ${directory} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
