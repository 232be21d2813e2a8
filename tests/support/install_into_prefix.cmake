# The consumer tests' first step (package/run_consumer.cmake, host_glad/run_host_glad.cmake):
# installs the build tree BUILD_DIR into a fresh scratch prefix, WORK_DIR/prefix.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
