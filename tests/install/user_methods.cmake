# cmake -P script: install erkn's runtime and generator components from the build tree into
# PREFIX, then build the user's project (user_methods/) against the installed package only:
# - with sb3a.spec (two explicit methods): builds, and the program runs SB3A through
#   Method::by_name at its certified order (slopes within 0.15), and writes methods.json;
# - with raised.spec (SB3A claiming order 5): the build fails naming the method and a tree;
# - the time erkn_add_methods adds: the build with sb3a.spec minus the build without specs.
# - the build tree's erkn list / run --methods-file take methods.json; a changed digit is refused.
# Inputs: BUILD_DIR, PREFIX, WORK, CXX, SOURCE (tests/install/user_methods), ERKN_CLI.
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
# Configures and builds the project in WORK/name with SPECS; sets seconds to the build's wall
# time (configure excluded), rc, out.
function(build_project name specs method)
  run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/${name} -DCMAKE_PREFIX_PATH=${PREFIX}
      -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release "-DSPECS=${specs}"
      -DMETHOD_NAME=${method})
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/${name} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(TIMESTAMP t1 "%s")
  math(EXPR s "${t1} - ${t0}")
  set(seconds ${s} PARENT_SCOPE)
  set(rc ${rc} PARENT_SCOPE)
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${PREFIX} ${WORK})
foreach(component runtime generator)
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --component ${component} --prefix ${PREFIX})
endforeach()
if(NOT EXISTS ${PREFIX}/bin/erkn-generate)
  message(FATAL_ERROR "the generator component installed no bin/erkn-generate")
endif()

build_project(plain "" "")
set(plain_seconds ${seconds})
build_project(sb3a ${SOURCE}/sb3a.spec SB3A)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the project with sb3a.spec did not build:\n${out}")
endif()
math(EXPR added "${seconds} - ${plain_seconds}")
message(STATUS "build time: ${plain_seconds} s without erkn_add_methods, ${seconds} s with two "
               "methods: erkn_add_methods adds ${added} s (whole seconds)")
run(${WORK}/sb3a/app)
message(STATUS "${out}")
if(NOT EXISTS ${WORK}/sb3a/erkn_methods_app/methods.json)
  message(FATAL_ERROR "erkn_add_methods(... JSON) wrote no methods.json")
endif()
# Only a changed spec reruns the generator.
run(${CMAKE_COMMAND} --build ${WORK}/sb3a)
if(out MATCHES "erkn-generate")
  message(FATAL_ERROR "an unchanged spec reran erkn-generate:\n${out}")
endif()

build_project(raised ${SOURCE}/raised.spec SB3A5)
if(rc EQUAL 0 OR NOT out MATCHES "SB3A5: claimed order 5 fails at tree f")
  message(FATAL_ERROR "raised.spec: expected a failed build naming SB3A5 and a tree, got exit "
                      "${rc}:\n${out}")
endif()
string(REGEX MATCH "SB3A5: claimed order 5 fails at tree [^:]*" refusal "${out}")
message(STATUS "refused as expected: ${refusal}")

# The CLI takes the methods as data: erkn list and erkn run --methods-file (the build tree's erkn).
set(json ${WORK}/sb3a/erkn_methods_app/methods.json)
run(${ERKN_CLI} list --methods-file ${json})
if(NOT out MATCHES "\nSB3A +explicit +5 +4 " OR NOT out MATCHES "\nSB3A_M4 +explicit +4 +4 ")
  message(FATAL_ERROR "erkn list --methods-file does not list SB3A and SB3A_M4:\n${out}")
endif()
# tableau, advise and stability take them too.
run(${ERKN_CLI} tableau SB3A --v 0.5 --methods-file ${json})
if(NOT out MATCHES "\"method\": \"SB3A\"")
  message(FATAL_ERROR "erkn tableau SB3A --methods-file: no SB3A tableau:\n${out}")
endif()
run(${ERKN_CLI} advise SB3A --h 0.1 --spectrum 1,4 --methods-file ${json})
run(${ERKN_CLI} stability SB3A --grid 16 --out ${WORK}/stability --methods-file ${json})
run(${ERKN_CLI} run --methods-file ${json} --problems P3 --methods SB3A,Strang --steps 1/8,1/16
    --out ${WORK}/run)
file(READ ${WORK}/run/results.md results)
if(NOT results MATCHES "\n\\| SB3A \\| explicit")
  message(FATAL_ERROR "erkn run --methods-file: no SB3A row in results.md")
endif()
# One digit of SB3A's d_1 changed (the 6th significant one): refused, naming the condition.
file(READ ${json} text)
string(REGEX REPLACE "(\"d\": \\[-0\\.0410958)9" "\\18" changed "${text}")
if(changed STREQUAL text)
  message(FATAL_ERROR "the digit to change was not found in ${json}")
endif()
file(WRITE ${WORK}/changed.json "${changed}")
execute_process(COMMAND ${ERKN_CLI} list --methods-file ${WORK}/changed.json RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "SB3A': claims order 4 .*but tree \\[")
  message(FATAL_ERROR "a changed digit: expected a refusal naming a tree, got ${rc}: ${err}")
endif()
message(STATUS "changed digit refused: ${err}")
