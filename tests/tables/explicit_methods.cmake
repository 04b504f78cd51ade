# Explicit methods through the generator: Strang certifies order 2 exactly and its V -> 0 limit
# (position Verlet) order 2; Yoshida's triple jump order 4 in 60-digit arithmetic; both are listed
# as explicit with entire coefficients (no poles); raising Yoshida's order is refused at a tree.
# Yoshida6 (the triple jump of Yoshida4) certifies exactly order 6: the conditions of the trees
# with M-vertices (power >= 5) hold for a composition known to be of order 6, and power 7 fails.
# Yoshida4dec (16-digit decimals) is polished onto its order conditions and emits exactly
# Yoshida4's doubles; a drift or a kick off by 1e-6 is refused. SABA2 certifies
# its claimed generalized order (4, 2), and a claim of 5 for eps^1 is refused at a tree.
include(${CMAKE_CURRENT_LIST_DIR}/spec_checks.cmake)
derive_spec(md)
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
file(READ ${WORKDIR}/ok/src/tables.cpp cpp)
set(arrays "\n\nconstexpr double c\\[\\] = {[^}]*};\nconstexpr double d\\[\\] = {[^}]*}")
string(REGEX MATCH "namespace Yoshida4 {${arrays}" exact "${cpp}")
string(REGEX MATCH "namespace Yoshida4dec {${arrays}" polished "${cpp}")
string(REPLACE "Yoshida4dec" "Yoshida4" polished "${polished}")
if(exact STREQUAL "" OR NOT exact STREQUAL polished)
  message(FATAL_ERROR "polished Yoshida4dec differs from Yoshida4:\n${exact}\n${polished}")
endif()
if(NOT md MATCHES "## Yoshida4dec[^#]*decimals polished[^#]*symmetry kept[^#]*\\*\\*order 4\\*\\*")
  message(FATAL_ERROR "derivation.md does not show Yoshida4dec polished and of order 4")
endif()
if(NOT md MATCHES "## SABA2[^#]*eps\\^1: 4, eps\\^2: 2")
  message(FATAL_ERROR "derivation.md does not show SABA2's generalized order (4, 2)")
endif()
if(NOT def MATCHES "ERKN_METHOD\\(Yoshida4, \"Yoshida4\", 3, 4, explicit\\)")
  message(FATAL_ERROR "methods.def lacks Yoshida4 as explicit of order 4: ${def}")
endif()
expect_raised_order_refused(Yoshida4 4 ".*has residual [-0-9.e]+ \\(certified order 4\\)")
file(READ ${SPEC} spec)

# Negative controls: a drift off by 1e-6 (the drifts no longer sum to 1), a kick off by 1e-6 (the
# decimals meet no order: refused at the tree f with the residual 1e-6), a generalized order
# raised by one.
string(REPLACE "0.6756035959798289, -0.1756035959798288" "0.6756045959798289, -0.1756035959798288"
       typo_drift "${spec}")
string(REPLACE "kick      1.3512071919596578," "kick      1.3512081919596578," typo_kick "${spec}")
string(REPLACE "generalized 4, 2" "generalized 5, 2" raised_g "${spec}")
foreach(case typo_drift typo_kick raised_g)
  if("${${case}}" STREQUAL "${spec}")
    message(FATAL_ERROR "${case}: the edit did not apply to ${SPEC}")
  endif()
  file(WRITE ${WORKDIR}/${case}.spec "${${case}}")
  execute_process(COMMAND ${GENERATOR} ${WORKDIR}/${case}.spec ${WORKDIR}/${case}
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  set(expect_typo_drift "Yoshida4dec: the drifts sum to 1.00000100*[0-9]*, not 1")
  set(expect_typo_kick "Yoshida4dec: claimed order 4 fails at tree f: .* has residual 1e-06 \\(certified order 0\\); the decimals do not meet the claim \\(polished onto the orders they meet, [0-9]+ conditions left out\\): a wrong claim or a transcription error")
  set(expect_raised_g "SABA2: claimed generalized order 5 for eps\\^1 is not certified \\(4\\): tree f")
  if(rc EQUAL 0 OR NOT err MATCHES "${expect_${case}}")
    message(FATAL_ERROR "${case}: expected a refusal matching '${expect_${case}}', got: ${err}")
  endif()
  message(STATUS "refused as expected: ${err}")
endforeach()
