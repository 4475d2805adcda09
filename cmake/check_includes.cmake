# Fails when a C/C++ source or header under ROOT/<FOLDERS> (|-separated) has an #include whose path
# contains "..": headers are included by their path from the repository root, which only the
# include directories of the file's own layer and those below resolve (cmake/layers.cmake).
string(REPLACE "|" ";" folders "${FOLDERS}")
set(bad "")
foreach(folder ${folders})
  file(GLOB_RECURSE files ${ROOT}/${folder}/*.c ${ROOT}/${folder}/*.h ${ROOT}/${folder}/*.cpp)
  foreach(f ${files})
    file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<][^\">]*\\.\\.")
    foreach(l ${lines})
      file(RELATIVE_PATH rel ${ROOT} ${f})
      string(STRIP "${l}" l)
      string(APPEND bad "  ${rel}: ${l}\n")
    endforeach()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "#include paths must not contain \"..\" (include by the path from the "
    "repository root, e.g. \"scenes/scene.h\"; a header of a higher layer is not reachable):\n${bad}")
endif()
