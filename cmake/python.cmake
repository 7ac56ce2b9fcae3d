# The Python package (python/, docs/python.md): which interpreter it is built for.
#
# penumbra_find_python() sets PENUMBRA_PYTHON_FOUND and, when found, finds Python3 (its interpreter
# and module development files) and pybind11. The interpreter is the first of
#   - Python3_EXECUTABLE, when the caller sets it (-DPython3_EXECUTABLE=...);
#   - /usr/bin/python3, Debian's own, for which scripts/setup.sh installs NumPy and pytest;
#   - every python3 on PATH,
# that can `import numpy`: a python3 first on PATH that lacks it (a pyenv or a venv) is passed over
# instead of building a module that cannot be tested or imported with NumPy. The choice is printed,
# and PENUMBRA_PYTHON_EXECUTABLE holds it for the tests. pybind11 is found as a CMake package
# (Debian's pybind11-dev), or where the interpreter's own pybind11 module says.

function(penumbra_python_usable interpreter out_var)
  execute_process(COMMAND ${interpreter} -c "import numpy, sys; print(sys.version_info[0])"
                  RESULT_VARIABLE result OUTPUT_VARIABLE major OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(result EQUAL 0 AND major STREQUAL "3")
    set(${out_var} TRUE PARENT_SCOPE)
  else()
    set(${out_var} FALSE PARENT_SCOPE)
  endif()
endfunction()

macro(penumbra_find_python)
  set(PENUMBRA_PYTHON_FOUND FALSE)
  set(candidates)
  if(Python3_EXECUTABLE)
    list(APPEND candidates ${Python3_EXECUTABLE})
  else()
    list(APPEND candidates /usr/bin/python3)
    string(REPLACE ":" ";" path_folders "$ENV{PATH}")
    foreach(folder ${path_folders})
      list(APPEND candidates ${folder}/python3)
    endforeach()
  endif()
  set(PENUMBRA_PYTHON_EXECUTABLE "")
  foreach(candidate ${candidates})
    if(EXISTS ${candidate} AND NOT PENUMBRA_PYTHON_EXECUTABLE)
      penumbra_python_usable(${candidate} usable)
      if(usable)
        set(PENUMBRA_PYTHON_EXECUTABLE ${candidate})
      endif()
    endif()
  endforeach()
  if(PENUMBRA_PYTHON_EXECUTABLE)
    set(Python3_EXECUTABLE ${PENUMBRA_PYTHON_EXECUTABLE} CACHE FILEPATH "the Python the penumbra module is built for" FORCE)
    find_package(Python3 COMPONENTS Interpreter Development.Module)
    execute_process(COMMAND ${PENUMBRA_PYTHON_EXECUTABLE} -c "import pybind11; print(pybind11.get_cmake_dir())"
                    RESULT_VARIABLE ignored
                    OUTPUT_VARIABLE pybind11_cmake_dir OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    find_package(pybind11 CONFIG HINTS ${pybind11_cmake_dir})
    if(Python3_FOUND AND pybind11_FOUND)
      set(PENUMBRA_PYTHON_FOUND TRUE)
      message(STATUS "penumbra Python package: for ${PENUMBRA_PYTHON_EXECUTABLE} (Python ${Python3_VERSION}, pybind11 ${pybind11_VERSION})")
    endif()
  endif()
  if(NOT PENUMBRA_PYTHON_FOUND)
    message(STATUS "penumbra Python package: not built (no python3 that can import numpy, no pybind11-dev, "
                   "or no Python headers: scripts/setup.sh installs them)")
  endif()
endmacro()
