# Generates the GL loader with glad2 (Debian `python3-glad`) into the build tree at build time and
# defines `zenith_glad`, an OBJECT library that zenith_sky compiles in.
#
# The loader takes a getProcAddress callback (gladLoadGL), so the same code runs on OSMesa, EGL or
# a host application's own context. The generated code is third party: it is compiled without the
# project's warning flags and its headers are SYSTEM. Its symbols (gladLoadGL, glad_gl*) are global:
# a host that links its own glad into the same binary would clash with them.
#
# Inputs (cache variables):
#   ZENITH_GLAD_PYTHON      a Python 3 that can `import glad`. Not the `python3` on PATH, which
#                           may be a pyenv/venv interpreter without Debian's dist-packages.
#   ZENITH_GLAD_EXECUTABLE  the glad2 command-line script (/usr/bin/glad from python3-glad).
#   ZENITH_GLAD_API         glad --api value.
#   ZENITH_GLAD_EXTENSIONS  comma-separated extensions to load besides the core API.
# Output:
#   zenith_glad             OBJECT library: add $<TARGET_OBJECTS:zenith_glad> to a target
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
    DEPENDS ${CMAKE_BINARY_DIR}/glad.stamp ${CMAKE_CURRENT_LIST_FILE}
    COMMENT "Generating GL loader with glad2 (${ZENITH_GLAD_API})"
    VERBATIM)

add_library(zenith_glad OBJECT ${_zenith_glad_outputs})
target_include_directories(zenith_glad SYSTEM PUBLIC ${ZENITH_GLAD_INCLUDE_DIR})
set_target_properties(zenith_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
