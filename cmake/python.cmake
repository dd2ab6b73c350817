# The Python package `proxima` (docs/python.md): pybind11 bindings over the library, numpy
# arrays in and out. The package is assembled in <build>/python/proxima/ (the pure-Python
# files of python/proxima/ beside the compiled extension _proxima), so
# `PYTHONPATH=<build>/python python3 -c "import proxima"` works without installing.
#
# Built against Debian's /usr/bin/python3 by default: python3-pybind11 and python3-numpy
# are built for it, and another python3 earlier on PATH may be a different interpreter.
# -DPython_EXECUTABLE=… picks another one.
if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter the proxima module is built for")
endif()
find_package(Python 3.8 QUIET COMPONENTS Interpreter Development.Module)
if(Python_FOUND)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
# Off by default in sanitizer builds: an ASan-instrumented module cannot be loaded into an
# uninstrumented interpreter (the runtime must come first), so `make asan` would fail.
set(PROXIMA_PYTHON_DEFAULT OFF)
if(Python_FOUND AND pybind11_FOUND AND NOT PROXIMA_FUZZ AND NOT PROXIMA_SANITIZE)
  set(PROXIMA_PYTHON_DEFAULT ON)
endif()
option(PROXIMA_PYTHON "Build the Python module (pybind11 + numpy, docs/python.md)" ${PROXIMA_PYTHON_DEFAULT})
if(NOT PROXIMA_PYTHON)
  if(NOT PROXIMA_PYTHON_DEFAULT)
    if(PROXIMA_SANITIZE OR PROXIMA_FUZZ)
      message(STATUS "Python module: off in sanitizer builds (-DPROXIMA_PYTHON=ON to force)")
    else()
      message(STATUS "Python module: off (needs pybind11-dev, python3-dev for ${Python_EXECUTABLE}; "
                     "scripts/install-deps.sh installs them)")
    endif()
  endif()
  return()
endif()
if(NOT pybind11_FOUND)
  message(FATAL_ERROR "PROXIMA_PYTHON=ON but pybind11 or the Python headers were not found "
                      "(Debian: pybind11-dev python3-dev)")
endif()
message(STATUS "Python module: ${Python_EXECUTABLE} (Python ${Python_VERSION}, pybind11 ${pybind11_VERSION})")

# A shared module links the static library: its code must be position independent.
# -fno-semantic-interposition keeps the calls inside the library inlinable and direct,
# as they are without -fPIC.
set_target_properties(proxima_lib PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_compile_options(proxima_lib PRIVATE -fno-semantic-interposition)

include(cmake/sources_python.cmake)
proxima_check_sources(LIST_FILE cmake/sources_python.cmake DIRS python/src SOURCES ${PROXIMA_PYTHON_SOURCES})

set(PROXIMA_PYTHON_DIR ${PROJECT_BINARY_DIR}/python)
# NO_EXTRAS: no LTO and no stripping, so the extension calls the very library code the
# command line runs (the overhead benchmark compares the two).
pybind11_add_module(_proxima MODULE NO_EXTRAS ${PROXIMA_PYTHON_SOURCES})
target_compile_options(_proxima PRIVATE ${PROXIMA_WARNINGS})
target_include_directories(_proxima PRIVATE ${CMAKE_SOURCE_DIR}/python/src)
target_link_libraries(_proxima PRIVATE proxima_lib)
set_target_properties(_proxima PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROXIMA_PYTHON_DIR}/proxima)

set(PROXIMA_PYTHON_COPIES)
foreach(file ${PROXIMA_PYTHON_FILES})
  file(RELATIVE_PATH rel ${CMAKE_SOURCE_DIR}/python ${CMAKE_SOURCE_DIR}/${file})
  add_custom_command(OUTPUT ${PROXIMA_PYTHON_DIR}/${rel}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${CMAKE_SOURCE_DIR}/${file} ${PROXIMA_PYTHON_DIR}/${rel}
    DEPENDS ${CMAKE_SOURCE_DIR}/${file} COMMENT "python package: ${rel}")
  list(APPEND PROXIMA_PYTHON_COPIES ${PROXIMA_PYTHON_DIR}/${rel})
endforeach()
add_custom_target(proxima_python_files ALL DEPENDS ${PROXIMA_PYTHON_COPIES})
add_dependencies(_proxima proxima_python_files)

# The pytest suite (tests/python/), one ctest test per file, with this build's package and
# command line (tests compare against `proxima render`).
if(PROXIMA_BUILD_TESTS)
  file(GLOB PROXIMA_PYTHON_TESTS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/python/test_*.py)
  foreach(test ${PROXIMA_PYTHON_TESTS})
    get_filename_component(name ${test} NAME_WE)
    add_test(NAME python.${name}
      COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${test}
      WORKING_DIRECTORY ${PROJECT_BINARY_DIR})
    set_tests_properties(python.${name} PROPERTIES TIMEOUT 600
      ENVIRONMENT "PYTHONPATH=${PROXIMA_PYTHON_DIR};PROXIMA_CLI=$<TARGET_FILE:proxima>;PYTHONDONTWRITEBYTECODE=1")
  endforeach()
endif()
