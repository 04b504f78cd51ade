# erkn-mpi scaling on 1 rank, then report: the strong-scaling table starts with the serial
# Integrator's row (the baseline without MPI), whose final state agrees with the 1-rank
# distributed run (sum of q within 1e-12 relative: the same steps, other transforms), and the
# rows of a 2-rank run (appended to the same table) compare against it. `erkn-mpi versus` on 1 rank
# adds a row per method (an explicit and an implicit one): 1 rank against the serial Integrator,
# final states within 1e-12. Negative control: a table without the serial row (the 2-rank rows
# only) gives no serial row and no such column, and no per-method section.
# -DMPIEXEC=... -DERKN_MPI=... -DWORK=dir
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(ranks 1 2)
  execute_process(COMMAND ${MPIEXEC} -np ${ranks} --oversubscribe ${ERKN_MPI} scaling
                          --table ${WORK}/table.tsv --grid 16x16 --weak-rows 8 --steps 4
                          --repeats 1 --h 0.01
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "scaling on ${ranks} ranks failed (${status}): ${out}${err}")
  endif()
  if(ranks EQUAL 2)
    file(STRINGS ${WORK}/table.tsv rows REGEX "^(strong|weak)\t.*\t2\t")
    string(REPLACE ";" "\n" rows "${rows}")
    file(WRITE ${WORK}/two_ranks.tsv "${rows}\n")
  endif()
endforeach()
execute_process(COMMAND ${MPIEXEC} -np 1 ${ERKN_MPI} versus --table ${WORK}/table.tsv
                        --methods "Strang;SERKN2s4" --grid 16x16 --steps 4 --repeats 1 --rounds 2
                        --h 0.01
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "versus failed (${status}): ${out}${err}")
endif()
execute_process(COMMAND ${ERKN_MPI} report --table ${WORK}/table.tsv --out ${WORK}/report.md
                RESULT_VARIABLE status)
execute_process(COMMAND ${ERKN_MPI} report --table ${WORK}/two_ranks.tsv --out ${WORK}/control.md
                RESULT_VARIABLE control_status)
if(NOT status EQUAL 0 OR NOT control_status EQUAL 0)
  message(FATAL_ERROR "report failed: ${status} ${control_status}")
endif()
file(READ ${WORK}/report.md report)
set(number "[0-9.]+e[-+][0-9]+")
if(NOT report MATCHES "\\| serial Integrator \\| 16x16 \\| 256 \\| 256 \\| [^\n]*\\| (${number}) \\|\n\\| 1 \\| 16x16")
  message(FATAL_ERROR "no serial row first in the strong table:\n${report}")
endif()
if(NOT CMAKE_MATCH_1 LESS 1e-12)
  message(FATAL_ERROR "serial and 1-rank final states differ by ${CMAKE_MATCH_1}")
endif()
if(NOT report MATCHES "serial Integrator's time / time" OR NOT report MATCHES "\n\\| 2 \\| 16x16")
  message(FATAL_ERROR "the 2-rank rows or the comparison column are missing:\n${report}")
endif()
foreach(method Strang SERKN2s4)
  if(NOT report MATCHES "\n\\| ${method} \\| 16x16 \\| [0-9.]+ \\| [0-9.]+ \\| [0-9.]+ \\| [^|]+\\| [^|]+\\| (${number}) \\|")
    message(FATAL_ERROR "no per-method row for ${method}:\n${report}")
  endif()
  if(NOT CMAKE_MATCH_1 LESS 1e-12)
    message(FATAL_ERROR "${method}: serial and 1-rank final states differ by ${CMAKE_MATCH_1}")
  endif()
endforeach()
file(READ ${WORK}/control.md control)
if(control MATCHES "serial Integrator \\|" OR control MATCHES "serial Integrator's time / time"
   OR control MATCHES "per method")
  message(FATAL_ERROR "a table without the serial row still shows one:\n${control}")
endif()
