# Generates the GL loader with glad2 (Debian `python3-glad`) into the build tree at build time and
# defines `zenith_glad`, an OBJECT library that zenith_sky compiles in.
#
# The loader takes a getProcAddress callback (zenith_gladLoadGL), so the same code runs on OSMesa,
# EGL or a host application's own context. The generated code is third party: it is compiled
# without the project's warning flags and its headers are SYSTEM.
#
# The loader is private to zenith: after generating, cmake/ZenithGladPrefix.cmake renames every
# symbol glad makes global (gladLoadGL, gladLoadGLUserPtr, glad_gl*, GLAD_GL_*) to zenith_glad* /
# ZENITH_GLAD_GL_*. glad's own names would clash with a host that links its own glad (a GL 3.3
# host failed to link with 358 "multiple definition" errors), or worse, a host glad covering every
# function zenith uses won the link and zenith ran on the host's pointers, loaded for the host's
# context. tests/host_glad (CTest package_host_glad_gl) links both kinds of host. Why a prefix:
#  - glad's --mx (python3-glad 2.0.2 has it) puts the pointers in a GladGLContext struct, so every
#    call site becomes gl->Clear(...) (thousands, shaders' host code and tests included), and its
#    entry points (gladLoadGLContext, ...) are still global glad names that a host using --mx
#    would clash with;
#  - symbol visibility or objcopy --prefix-symbols act on the objects, not the names: a static
#    libzenith_sky.a is never linked before the host's link, so hidden visibility hides nothing,
#    and a shared build would also have to hide the pointers from zenith's own GL tests;
#  - renaming the generated text keeps the `#define glClear zenith_glad_glClear` macros, so
#    zenith's code still writes plain GL calls, and it holds for static and shared builds alike:
#    the symbols are zenith_glad* whichever library they end up in.
# The header stays at glad/gl.h in the build tree only (it is not installed): zenith's public
# headers include no GL header, so a host may use any loader of its own.
#
# Inputs (cache variables):
#   ZENITH_GLAD_PYTHON      a Python 3 that can `import glad`. Not the `python3` on PATH, which
#                           may be a pyenv/venv interpreter without Debian's dist-packages.
#   ZENITH_GLAD_EXECUTABLE  the glad2 command-line script (/usr/bin/glad from python3-glad).
#   ZENITH_GLAD_API         glad --api value.
#   ZENITH_GLAD_EXTENSIONS  comma-separated extensions to load besides the core API.
# Output:
#   zenith_glad             OBJECT library: add $<TARGET_OBJECTS:zenith_glad> to a target
#                           (entry points zenith_gladLoadGL / zenith_gladLoadGLUserPtr)
#   ZENITH_GLAD_INCLUDE_DIR directory holding glad/gl.h and KHR/khrplatform.h
include_guard(GLOBAL)

set(ZENITH_GLAD_PYTHON /usr/bin/python3 CACHE FILEPATH
    "Python 3 interpreter that has the glad module (Debian: python3-glad)")
set(ZENITH_GLAD_EXECUTABLE /usr/bin/glad CACHE FILEPATH "glad2 command-line script")
set(ZENITH_GLAD_API "gl:core=4.5" CACHE STRING "glad --api: GL API, profile and version")
# Beyond 4.5 core: SPIR-V and #include for shaders, anisotropic filtering (core only in 4.6).
string(JOIN "," _zenith_glad_default_extensions
    GL_ARB_gl_spirv GL_ARB_shading_language_include
    GL_ARB_texture_filter_anisotropic GL_EXT_texture_filter_anisotropic GL_KHR_debug)
set(ZENITH_GLAD_EXTENSIONS "${_zenith_glad_default_extensions}" CACHE STRING
    "glad --extensions: comma-separated GL extensions to load")

# Fail at configure time, with the fix, rather than with a Python traceback mid-build.
execute_process(
    COMMAND ${ZENITH_GLAD_PYTHON} -c "import glad, glad.generator.c"
    RESULT_VARIABLE _zenith_glad_import_result
    OUTPUT_QUIET ERROR_VARIABLE _zenith_glad_import_error)
if(NOT EXISTS "${ZENITH_GLAD_EXECUTABLE}")
    string(APPEND _zenith_glad_import_error "  and ${ZENITH_GLAD_EXECUTABLE} does not exist\n")
endif()
if(NOT _zenith_glad_import_result EQUAL 0 OR NOT EXISTS "${ZENITH_GLAD_EXECUTABLE}")
    message(FATAL_ERROR
        "zenith: the GL loader is generated with glad2, which was not found.\n"
        "  tried: ${ZENITH_GLAD_PYTHON} -c 'import glad' -> ${_zenith_glad_import_result}\n"
        "  ${_zenith_glad_import_error}"
        "  fix:   apt-get install python3-glad, or set ZENITH_GLAD_PYTHON / "
        "ZENITH_GLAD_EXECUTABLE (scripts/install-deps.sh installs it).")
endif()

set(_zenith_glad_dir ${CMAKE_BINARY_DIR}/glad)
set(ZENITH_GLAD_INCLUDE_DIR ${_zenith_glad_dir}/include)
set(_zenith_glad_outputs
    ${_zenith_glad_dir}/include/glad/gl.h
    ${_zenith_glad_dir}/include/KHR/khrplatform.h
    ${_zenith_glad_dir}/src/gl.c)
set(_zenith_glad_command
    ${ZENITH_GLAD_PYTHON} ${ZENITH_GLAD_EXECUTABLE}
    --api ${ZENITH_GLAD_API} --extensions ${ZENITH_GLAD_EXTENSIONS}
    --out-path ${_zenith_glad_dir} --reproducible --quiet c)

# The stamp changes only when the command does, so editing a cache variable regenerates the loader
# and nothing else does. --reproducible: use the specs bundled with python3-glad, never the network.
string(JOIN " " _zenith_glad_command_line ${_zenith_glad_command})
file(CONFIGURE OUTPUT ${CMAKE_BINARY_DIR}/glad.stamp CONTENT "${_zenith_glad_command_line}\n")

add_custom_command(
    OUTPUT ${_zenith_glad_outputs}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${_zenith_glad_dir}
    COMMAND ${_zenith_glad_command}
    COMMAND ${CMAKE_COMMAND} -DDIR=${_zenith_glad_dir}
            -P ${CMAKE_CURRENT_LIST_DIR}/ZenithGladPrefix.cmake
    DEPENDS ${CMAKE_BINARY_DIR}/glad.stamp ${CMAKE_CURRENT_LIST_FILE}
            ${CMAKE_CURRENT_LIST_DIR}/ZenithGladPrefix.cmake
    COMMENT "Generating GL loader with glad2 (${ZENITH_GLAD_API})"
    VERBATIM)

add_library(zenith_glad OBJECT ${_zenith_glad_outputs})
target_include_directories(zenith_glad SYSTEM PUBLIC ${ZENITH_GLAD_INCLUDE_DIR})
set_target_properties(zenith_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
