# Installs the build tree into a scratch prefix, builds tests/host_glad against it (hosts that link
# their own glad), runs each host, and checks that no installed library defines a global symbol
# under glad's own names.
# Arguments: -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DNM=... -DGLAD_PYTHON=...
#            -DGLAD_EXECUTABLE=... -DGLAD_EXTENSIONS=... [-DCONSUMER_FLAGS=...]
include(${CMAKE_CURRENT_LIST_DIR}/../support/install_into_prefix.cmake)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        -DHOST_GLAD_PYTHON=${GLAD_PYTHON} -DHOST_GLAD_EXECUTABLE=${GLAD_EXECUTABLE}
                        -DHOST_GLAD_45_EXTENSIONS=${GLAD_EXTENSIONS}
                        "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}" "-DCMAKE_C_FLAGS=${CONSUMER_FLAGS}"
                        "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the host with find_package(zenith) failed (${rc})")
endif()
# -k 0: show both hosts' link results.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build -- -k 0 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the hosts that link their own glad with zenith failed (${rc})")
endif()
foreach(host host_glad33 host_glad45)
    execute_process(COMMAND ${WORK_DIR}/build/${host} RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${host} ran but failed (${rc})")
    endif()
endforeach()

# zenith's loader is renamed (cmake/ZenithGlad.cmake): its globals are zenith_glad*/ZENITH_GLAD_*.
file(GLOB libraries ${WORK_DIR}/prefix/lib*/libzenith*)
if(NOT libraries)
    message(FATAL_ERROR "no libzenith* installed under ${WORK_DIR}/prefix")
endif()
set(found_loader FALSE)
foreach(library IN LISTS libraries)
    execute_process(COMMAND ${NM} -C -g --defined-only ${library}
                    OUTPUT_VARIABLE symbols RESULT_VARIABLE rc ERROR_QUIET)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${NM} ${library} failed (${rc})")
    endif()
    string(REGEX MATCHALL "[ \t](glad[A-Z_][A-Za-z0-9_]*|GLAD_GL_[A-Za-z0-9_]*)" clashing
           "${symbols}")
    if(clashing)
        list(LENGTH clashing count)
        list(GET clashing 0 first)
        message(FATAL_ERROR
                "${library} defines ${count} global symbols under glad's names (first:${first})")
    endif()
    if(symbols MATCHES "[ \t]zenith_gladLoadGL\n")
        set(found_loader TRUE)
    endif()
endforeach()
if(NOT found_loader)
    message(FATAL_ERROR "no installed library defines zenith_gladLoadGL: was the loader renamed?")
endif()
