# The install-and-consume test (ctest label `install`), run as `cmake -P` with
#   BUILD_DIR     the built reftrack tree       CONSUMER_DIR  tests/install/consumer
#   WORK_DIR      scratch folder (recreated)    LAUNCHER      compiler launcher (ccache) or empty
#   README        README.md, which must quote the consumer's main.cpp verbatim
#   PYTHON        python3 of the Python module (empty: built without it)
#   PYTHON_DIR    where the install puts the module, relative to the prefix
# It installs the build into WORK_DIR/prefix, configures and builds the consumer as a separate
# project against that prefix only (find_package(reftrack)), makes a simulated clip and its map
# with the installed `reftrack`, and runs the consumer on the clip: it must exit 0 and print a
# pose for most frames.
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR CONSUMER_DIR WORK_DIR README)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "InstallConsumerTest.cmake: -D${var}=... is required")
  endif()
endforeach()
file(READ ${CONSUMER_DIR}/main.cpp example)
file(READ ${README} readme)
string(FIND "${readme}" "```cpp\n${example}```" quoted)
if(quoted EQUAL -1)
  message(FATAL_ERROR "README.md does not quote ${CONSUMER_DIR}/main.cpp verbatim")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(step name)
  string(TIMESTAMP start "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(TIMESTAMP stop "%s")
  math(EXPR seconds "${stop} - ${start}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} failed (exit ${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${name}: ${seconds} s")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file include/engine/api/Tracker.hpp include/render/CameraProjection.hpp bin/reftrack)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "install: ${prefix}/${file} missing")
  endif()
endforeach()
file(GLOB_RECURSE configs ${prefix}/*/reftrackConfig.cmake)
if(NOT configs)
  message(FATAL_ERROR "install: no reftrackConfig.cmake under ${prefix}")
endif()

# The Python module, imported from the prefix alone (its Python path; not the build tree's).
if(PYTHON)
  foreach(file ${PYTHON_DIR}/reftrack.pyi)
    if(NOT EXISTS ${prefix}/${file})
      message(FATAL_ERROR "install: ${prefix}/${file} missing")
    endif()
  endforeach()
  step("import reftrack" ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR}
       ${PYTHON} -c "import reftrack\nprint(reftrack.__file__, reftrack.__version__)")
  string(FIND "${step_output}" "${prefix}/${PYTHON_DIR}/reftrack." from_prefix)
  if(from_prefix EQUAL -1)
    message(FATAL_ERROR "import reftrack: not the installed module: ${step_output}")
  endif()
  # Installed under CMake's default prefix (/usr/local) or /usr, python3 finds it unaided.
  step("python3's path" ${CMAKE_COMMAND} -E env --unset=PYTHONPATH ${PYTHON} -c
       "import sys\nprint(*sys.path, sep='\\n')")
  string(REPLACE "\n" ";" python_path "${step_output}")
  foreach(system_prefix /usr/local /usr)
    if(NOT "${system_prefix}/${PYTHON_DIR}" IN_LIST python_path)
      message(FATAL_ERROR "${system_prefix}/${PYTHON_DIR} is not on ${PYTHON}'s path: "
                          "${step_output}")
    endif()
  endforeach()
endif()

# Only the temporary prefix: no package registry, so the build tree cannot stand in for it.
set(configure_args -S ${CONSUMER_DIR} -B ${WORK_DIR}/consumer-build -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
step("configure consumer" ${CMAKE_COMMAND} ${configure_args})
step("build consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer-build -j 2)
step("render link check" ${WORK_DIR}/consumer-build/render_link_check)

set(reftrack ${prefix}/bin/reftrack)
step("simulate" ${reftrack} simulate --preset handheld --frames 40 --size 320x240 --out
     ${WORK_DIR}/clip)
step("prepare" ${reftrack} prepare --camera ${WORK_DIR}/clip/camera.yml
     --ref ${WORK_DIR}/clip/reference_a.png --ref ${WORK_DIR}/clip/reference_b.png
     --marker DICT_6X6_250:23:0.2 --out ${WORK_DIR}/map)
step("poses" ${WORK_DIR}/consumer-build/poses ${WORK_DIR}/map "${WORK_DIR}/clip/frames/*.png")
message(STATUS "poses printed:\n${step_output}")
string(REGEX MATCHALL "\n?[0-9]+ tracking t [^\n]*" posed "${step_output}")
list(LENGTH posed tracked)
string(REGEX MATCH "([0-9]+) of ([0-9]+) frames tracked" summary "${step_output}")
if(NOT summary OR NOT CMAKE_MATCH_2 EQUAL 40 OR NOT CMAKE_MATCH_1 EQUAL tracked)
  message(FATAL_ERROR "poses: expected 40 frames and a summary matching the ${tracked} poses")
endif()
# Measured on this clip: 40 of 40 frames posed (sim seed fixed); fewer than 36 is a failure.
if(tracked LESS 36)
  message(FATAL_ERROR "poses: only ${tracked} of 40 frames posed")
endif()
