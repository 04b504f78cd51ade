# erkn_add_methods(<target> SPECS <file>... [JSON]): a program's own methods, certified.
#
# At build time, and again only when a spec changes, runs the installed erkn-generate on the
# spec files (the language: docs/user-methods.md), compiles the emitted tables into <target> and
# adds them to erkn's registry at program start: erkn::Method::by_name("MyMethod") and
# erkn::Method::all() list them beside erkn's own. A spec whose claimed order is not certified
# fails the build; erkn-generate's message names the method and the first failing tree.
# JSON: also writes the explicit methods as data (methods.json, for Method::load and Python's
# erkn.load_methods). The outputs (erkn_methods.cpp, derivation.md with every condition checked,
# methods.json) are in ${CMAKE_CURRENT_BINARY_DIR}/erkn_methods_<target>/.
function(erkn_add_methods target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "JSON" "" "SPECS")
  if(NOT TARGET ${target})
    message(FATAL_ERROR "erkn_add_methods: '${target}' is not a target")
  endif()
  if(NOT arg_SPECS OR arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "erkn_add_methods(${target} SPECS <file>... [JSON]): no SPECS given, or "
                        "unknown arguments '${arg_UNPARSED_ARGUMENTS}'")
  endif()
  set(specs "")
  foreach(spec IN LISTS arg_SPECS)
    get_filename_component(spec "${spec}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND specs "${spec}")
  endforeach()
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/erkn_methods_${target}")
  set(outputs "${dir}/erkn_methods.cpp" "${dir}/derivation.md")
  set(json "")
  if(arg_JSON)
    set(json --json)
    list(APPEND outputs "${dir}/methods.json")
  endif()
  add_custom_command(OUTPUT ${outputs}
    COMMAND erkn::erkn-generate ${specs} --out "${dir}" ${json}
    DEPENDS ${specs} erkn::erkn-generate
    COMMENT "erkn-generate: deriving and certifying the methods of ${arg_SPECS}"
    VERBATIM)
  target_sources(${target} PRIVATE "${dir}/erkn_methods.cpp")
  target_link_libraries(${target} PRIVATE erkn::runtime)
endfunction()
