# One INTERFACE target carries the project's warning flags; every zenith target links it
# PRIVATE so consumers of the installed package never inherit them.
add_library(zenith_warnings INTERFACE)
target_compile_options(zenith_warnings INTERFACE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wnon-virtual-dtor
    $<$<BOOL:${ZENITH_WERROR}>:-Werror>)
install(TARGETS zenith_warnings EXPORT zenithTargets)
