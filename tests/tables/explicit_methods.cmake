# Explicit methods through the generator: Strang certifies order 2 exactly and its V -> 0 limit
# (position Verlet) order 2; Yoshida's triple jump order 4 in 60-digit arithmetic; both are listed
# as explicit with entire coefficients (no poles); raising Yoshida's order is refused at a tree.
# Yoshida6 (the triple jump of Yoshida4) certifies exactly order 6: the conditions of the trees
# with M-vertices (power >= 5) hold for a composition known to be of order 6, and power 7 fails.
execute_process(COMMAND ${GENERATOR} ${SPEC} ${WORKDIR}/ok RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "erkn-generate failed: ${err}")
endif()
file(READ ${WORKDIR}/ok/derivation.md md)
file(READ ${WORKDIR}/ok/include/erkn/generated/methods.def def)
foreach(expect
    "## Strang[^#]*exact arithmetic[^#]*\\*\\*order 2\\*\\*[^#]*PositionVerlet \\(Nystrom trees, V\\^0\\): order 2"
    "## Yoshida4[^#]*60-digit CLN arithmetic[^#]*\\*\\*order 4\\*\\*"
    "## Yoshida4[^#]*abar33 = `0`[^#]*Real poles in \\(0, 200\\]: none"
    "## Yoshida6[^#]*\\*\\*order 6\\*\\*[^#]*\\| 7 \\| `f` \\| `[^`]*` \\| \\*\\*")
  if(NOT md MATCHES "${expect}")
    message(FATAL_ERROR "derivation.md does not match '${expect}'")
  endif()
endforeach()
if(NOT def MATCHES "ERKN_METHOD\\(Yoshida4, \"Yoshida4\", 3, 4, explicit\\)")
  message(FATAL_ERROR "methods.def lacks Yoshida4 as explicit of order 4: ${def}")
endif()
file(READ ${SPEC} spec)
string(REGEX REPLACE "order     4\n" "order     5\n" raised "${spec}")
file(WRITE ${WORKDIR}/raised.spec "${raised}")
execute_process(COMMAND ${GENERATOR} ${WORKDIR}/raised.spec ${WORKDIR}/raised
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "Yoshida4: claimed order 5 fails at tree f.*has residual [-0-9.e]+ \\(certified order 4\\)")
  message(FATAL_ERROR "expected Yoshida4 of order 5 to be refused at a tree: ${err}")
endif()
message(STATUS "refused as expected: ${err}")
