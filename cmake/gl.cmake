# OpenGL side: the glad2 loader (generated at build time by Debian's python3-glad, never vendored),
# the GL context, techniques with their embedded shaders, and the gibench executable.

set(GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_DIR}/src/gl.c ${GLAD_DIR}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --reproducible --quiet --api gl:core=4.5 --out-path ${GLAD_DIR} c
  COMMENT "Generating the glad2 GL 4.5 core loader"
  VERBATIM)
add_library(gib_glad STATIC ${GLAD_DIR}/src/gl.c)
target_include_directories(gib_glad SYSTEM PUBLIC ${GLAD_DIR}/include)
target_compile_options(gib_glad PRIVATE -w)

# Shaders live next to their technique and are embedded as C strings (cmake/embed_shaders.cmake),
# with the headers they share with C (harness/gl/bindings.h, techniques/*/*_slots.h for GL slots,
# techniques/*/*_shared.h for other constants).
file(GLOB_RECURSE GIB_SHADERS CONFIGURE_DEPENDS
  ${CMAKE_SOURCE_DIR}/techniques/*.glsl ${CMAKE_SOURCE_DIR}/techniques/*.vert
  ${CMAKE_SOURCE_DIR}/techniques/*.frag ${CMAKE_SOURCE_DIR}/techniques/*.geom
  ${CMAKE_SOURCE_DIR}/techniques/*.comp ${CMAKE_SOURCE_DIR}/techniques/*_slots.h
  ${CMAKE_SOURCE_DIR}/techniques/*_shared.h
  ${CMAKE_SOURCE_DIR}/harness/gl/bindings.h)
set(GIB_SHADER_C ${CMAKE_BINARY_DIR}/generated/shaders.c)
# A CMake list would be split into several shell words: pass it '|'-separated.
string(REPLACE ";" "|" GIB_SHADER_LIST "${GIB_SHADERS}")
add_custom_command(
  OUTPUT ${GIB_SHADER_C}
  COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_SOURCE_DIR} -DOUT=${GIB_SHADER_C}
          "-DFILES=${GIB_SHADER_LIST}" -P ${CMAKE_SOURCE_DIR}/cmake/embed_shaders.cmake
  DEPENDS ${GIB_SHADERS} ${CMAKE_SOURCE_DIR}/cmake/embed_shaders.cmake
  COMMENT "Embedding shaders"
  VERBATIM)

# GL runtime: context (EGL, OSMesa), ledger, timers, shaders, view matrices, the GPU scene.
gib_layer_root(GIB_GL_ROOT gl harness/gl)
file(GLOB GIB_GL_SOURCES CONFIGURE_DEPENDS harness/gl/*.c)
add_library(gib_gl STATIC ${GIB_GL_SOURCES})
target_include_directories(gib_gl PUBLIC ${GIB_GL_ROOT})
# Linking -lOpenGL makes every OSMesa call a silent no-op (ARCHITECTURE.md, "Toolchain facts"). We
# link libEGL only and load every GL function through it or through libOSMesa, which
# harness/gl/context_osmesa.c opens with dlopen: only its header (GL/osmesa.h) is used at build time.
target_include_directories(gib_gl SYSTEM PRIVATE ${OSMESA_INCLUDE_DIRS})
target_link_libraries(gib_gl PUBLIC gib_scene gib_glad PkgConfig::EGL ${CMAKE_DL_LIBS})

# Techniques, their shared passes and embedded shaders; the registry.
gib_layer_root(GIB_TECH_ROOT techniques techniques)
file(GLOB GIB_TECH_SOURCES CONFIGURE_DEPENDS techniques/*.c techniques/*/*.c)
add_library(gib_techniques STATIC ${GIB_TECH_SOURCES} ${GIB_SHADER_C})
target_include_directories(gib_techniques PUBLIC ${GIB_TECH_ROOT})
target_link_libraries(gib_techniques PUBLIC gib_gl)

# The app: runner, CLI, matrix runner, CSV, reference cache (a library, so tests can run
# techniques as the CLI does), and the gibench executable.
gib_layer_root(GIB_APP_ROOT app harness/app)
file(GLOB GIB_APP_SOURCES CONFIGURE_DEPENDS harness/app/*.c)
list(FILTER GIB_APP_SOURCES EXCLUDE REGEX "/main\\.c$")
# Each technique's source hash (harness/reporting/source_hash.py), which every results row records so that
# the report can tell whether the row still describes the code.
find_package(Python3 REQUIRED COMPONENTS Interpreter)
file(GLOB_RECURSE GIB_TECH_ALL_FILES CONFIGURE_DEPENDS techniques/*.c techniques/*.h)
set(GIB_TECH_HASH_C ${CMAKE_BINARY_DIR}/generated/technique_hashes.c)
add_custom_command(
  OUTPUT ${GIB_TECH_HASH_C}
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/harness/reporting/source_hash.py --c ${GIB_TECH_HASH_C}
  DEPENDS ${GIB_TECH_ALL_FILES} ${GIB_SHADERS} ${CMAKE_SOURCE_DIR}/harness/reporting/source_hash.py
  COMMENT "Hashing each technique's sources"
  VERBATIM)
add_library(gib_app STATIC ${GIB_APP_SOURCES} ${GIB_TECH_HASH_C})
target_include_directories(gib_app PUBLIC ${GIB_APP_ROOT})
target_link_libraries(gib_app PUBLIC gib_techniques gib_reference)
add_executable(gibench harness/app/main.c)
target_link_libraries(gibench PRIVATE gib_app)
