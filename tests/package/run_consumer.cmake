# Installs the build tree into a scratch prefix, then configures, builds and runs the consumer.
# Arguments: -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... [-DCONSUMER_FLAGS=...]
include(${CMAKE_CURRENT_LIST_DIR}/../support/install_into_prefix.cmake)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        -DZENITH_HOST_EXAMPLE=${WORK_DIR}/prefix/share/zenith/examples/host_loop.cpp
                        "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
                        "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the consumer with find_package(zenith) failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the consumer failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the consumer ran but failed (${rc})")
endif()
# The installed example runs a few frames in its own (headless) GL context. Not under the
# sanitizers: llvmpipe's JIT code is not instrumented and libOSMesa leaks at exit.
if(CONSUMER_FLAGS STREQUAL "")
    execute_process(COMMAND ${WORK_DIR}/build/host_loop 0.5 ${WORK_DIR}/host_loop.png
                    RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "the installed host_loop example ran but failed (${rc})")
    endif()
endif()
