# Whether the Python module (python/) can be built: SFIT_BUILD_PYTHON and pybind11 and
# Python 3's headers found (Debian python3-pybind11, python3-dev). Sets SFIT_PYTHON, and
# position-independent code for the libraries the module links. Included from the top
# CMakeLists.txt before the libraries are defined.
set(SFIT_PYTHON OFF)
if(NOT SFIT_BUILD_PYTHON)
  message(STATUS "sfit: Python module off (SFIT_BUILD_PYTHON=OFF)")
  return()
endif()
if(SFIT_SANITIZE OR SFIT_FUZZ)
  message(STATUS "sfit: Python module off in sanitizer and fuzz builds "
                 "(the interpreter does not load the sanitizer runtime)")
  return()
endif()
# Debian's interpreter by default: its numpy, pytest and dask run the tests. Another one can be
# chosen with -DPython3_EXECUTABLE=... (pip install passes its own).
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the sfit module")
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
if(NOT Python3_FOUND)
  message(STATUS "sfit: Python module off: Python 3 interpreter and headers not found "
                 "(Debian: python3-dev)")
  return()
endif()
find_package(pybind11 2.6 CONFIG QUIET)
if(NOT pybind11_FOUND)
  message(STATUS "sfit: Python module off: pybind11 not found (Debian: python3-pybind11)")
  return()
endif()
set(SFIT_PYTHON ON)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
message(STATUS "sfit: Python module on (${Python3_EXECUTABLE}, pybind11 ${pybind11_VERSION})")
