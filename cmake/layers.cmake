# The build's layers (ARCHITECTURE.md, "Layers").
#
# gib_layer_root(VAR NAME FOLDER...) makes ${CMAKE_BINARY_DIR}/layers/NAME holding one link per
# FOLDER at its path from the repository root (layers/gl/harness/gl -> <source>/harness/gl) and
# sets VAR to it: a target given that include directory can write #include "harness/gl/view.h" and
# nothing outside those folders.
function(gib_layer_root var name)
  set(root ${CMAKE_BINARY_DIR}/layers/${name})
  foreach(folder ${ARGN})
    get_filename_component(parent ${root}/${folder} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    file(CREATE_LINK ${CMAKE_SOURCE_DIR}/${folder} ${root}/${folder} SYMBOLIC)
  endforeach()
  set(${var} ${root} PARENT_SCOPE)
endfunction()

# gib_check_includes(): a target every library depends on, refusing any #include "...": whose path
# climbs with "..": such a path reaches a file whatever include directories the target has, so it
# would bypass the layers. Runs at every build (it reads ~200 files).
function(gib_check_includes)
  add_custom_target(gib_check_includes ALL
    COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_SOURCE_DIR}
            -DFOLDERS=harness|scenes|reference|techniques|tests
            -P ${CMAKE_SOURCE_DIR}/cmake/check_includes.cmake
    COMMENT "Checking that no #include climbs out of its folder"
    VERBATIM)
  foreach(t gib_base gib_scene gib_reference gib_gl gib_techniques gib_app)
    add_dependencies(${t} gib_check_includes)
  endforeach()
endfunction()
