# Makes a glad2 C loader private to zenith: renames every identifier that glad gives external
# linkage, in the generated include/glad/gl.h and src/gl.c under DIR, in place.
#   glad*      (gladLoadGL, gladLoadGLUserPtr, the glad_gl* function pointers)  -> zenith_glad*
#   GLAD_GL_*  (the GLAD_GL_VERSION_4_5 / GLAD_GL_KHR_debug flags, and the header guard)
#                                                                              -> ZENITH_GLAD_GL_*
# glad's file-local helpers (glad_gl_load_*, ...) are renamed too, which does no harm. The `gl*`
# macros keep their names (`#define glClear zenith_glad_glClear`), so zenith's code writes plain
# GL. Macros that never reach the linker (GLAD_API_CALL, GLAD_PLATFORM_*, ...) are left alone:
# the header is not installed, so no translation unit sees it beside a host's glad.
# Run with cmake -P from ZenithGlad.cmake's generation step. Arguments: -DDIR=<glad --out-path>
if(NOT DIR)
    message(FATAL_ERROR "ZenithGladPrefix.cmake: DIR (glad's --out-path) is not set")
endif()
foreach(file include/glad/gl.h src/gl.c)
    file(READ ${DIR}/${file} text)
    # Whole identifiers only: the character before the match must not belong to an identifier.
    # (Both files begin with a comment, so no identifier starts the text.)
    string(REGEX REPLACE "([^A-Za-z0-9_])(glad[A-Z_])" "\\1zenith_\\2" text "${text}")
    string(REGEX REPLACE "([^A-Za-z0-9_])(GLAD_GL_)" "\\1ZENITH_\\2" text "${text}")
    # A glad that names its entry point differently would leave it global under its own name.
    if(NOT text MATCHES "zenith_gladLoadGL")
        message(FATAL_ERROR "ZenithGladPrefix.cmake: ${DIR}/${file} has no gladLoadGL to rename; "
                            "does this glad (${file}) name its loader differently?")
    endif()
    file(WRITE ${DIR}/${file} "${text}")
endforeach()
