# The project's compile rules, each once, as interface targets that a target links PRIVATE:
#
#   lr_warnings       the warning set; errors when LR_WERROR (on by default). Host code that may
#                     use exceptions (hal/host backends, host_sim, tests, benchmarks) links this.
#   lr_no_exceptions  the language subset of the core and the MCU side: no exceptions, no RTTI.
#   lr_strict         both: core/, hal/ (MCU side), firmware/ and code compiled as firmware.
#
# The same flags as lists, for commands that call a compiler themselves (custom commands):
#   LR_WARNING_FLAGS, LR_NO_EXCEPTIONS_FLAGS.
#
# Included by the top-level CMakeLists.txt; a project that builds parts of the tree on its own
# (tests/fuzz) includes it too. LR_WERROR is read when this file is included.
include_guard(GLOBAL)

set(LR_WARNING_FLAGS -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow)
if(NOT DEFINED LR_WERROR OR LR_WERROR)
  list(APPEND LR_WARNING_FLAGS -Werror)
endif()
set(LR_NO_EXCEPTIONS_FLAGS -fno-exceptions -fno-rtti)

add_library(lr_warnings INTERFACE)
target_compile_options(lr_warnings INTERFACE ${LR_WARNING_FLAGS})

# -fno-rtti is a C++ option (GCC warns about it for C sources).
add_library(lr_no_exceptions INTERFACE)
target_compile_options(lr_no_exceptions INTERFACE
  "$<$<COMPILE_LANGUAGE:CXX>:${LR_NO_EXCEPTIONS_FLAGS}>")

add_library(lr_strict INTERFACE)
target_link_libraries(lr_strict INTERFACE lr_warnings lr_no_exceptions)
