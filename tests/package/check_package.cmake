# cmake -DBUILD=<voxcast build> -DWORK=<scratch folder> -DCONSUMER=<consumer source>
#       -DGENERATOR=<generator> -P tests/package/check_package.cmake
#
# The package test: installs the build into WORK/prefix, configures and builds
# the consumer project against it (find_package(voxcast CONFIG)) and runs it.
# The consumer sees only the installed tree.
cmake_minimum_required(VERSION 3.25)
foreach(v BUILD WORK CONSUMER GENERATOR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_package: give -D${v}=...")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "check_package: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "check_package: ${what}: ok")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
foreach(f include/voxcast/hls/compositor.hpp include/voxcast/refmodel/bittrue/raycaster.hpp
          lib/cmake/voxcast/voxcastConfig.cmake bin/voxcast)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "check_package: the install lacks ${f}")
  endif()
endforeach()
run("configure the consumer" ${CMAKE_COMMAND} -S ${CONSUMER} -B ${WORK}/consumer -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/prefix)
run("build the consumer" ${CMAKE_COMMAND} --build ${WORK}/consumer)
run("run the consumer" ${WORK}/consumer/consumer)
message(STATUS "${last_output}")
