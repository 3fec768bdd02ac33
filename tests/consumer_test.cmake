# Installs the build tree into a scratch prefix, then configures, builds and runs two consumer
# projects against it with find_package: SOURCE (all packages) and TFETI_SOURCE (tfeti alone,
# which must not need Gmsh). They set no compiler or linker flags of their own: what they need
# comes with the exported targets. FLAGS (the sanitizer flags of a TFETI_SANITIZE build, or empty)
# must then appear on every compile and link line of the consumers. With SHARED_FROM the
# installed tree is a shared build made here (see below), so that both kinds are covered.
# GUIDE_SOURCE (examples/cpp, the C++ guide's programs) is a third project built the same way
# into WORK/guide; its MPI programs are run by tests of their own (tests/CMakeLists.txt), or,
# when GUIDE_RUN is given (an mpiexec command line ending in the rank count's flags), here, each
# program through it (GUIDE_ARGS_contact_cylinders: that program's arguments).
set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
function(run step)
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
# LAUNCHER: the compiler launcher of the package's build (e.g. ccache), used for every build made
# here, so that a rerun recompiles nothing that did not change.
set(launcher)
if(LAUNCHER)
  set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
# SHARED_FROM (a source tree): build the packages there first as shared libraries (tests off,
# with LAUNCHER), and install that build; then the installed tfeti_contact must run through its
# relative RPATH with the build tree gone.
if(SHARED_FROM)
  set(BUILD ${WORK}/package)
  run("${CMAKE_COMMAND};-S;${SHARED_FROM};-B;${BUILD};-DCMAKE_BUILD_TYPE=Release;-DBUILD_SHARED_LIBS=ON;-DTFETI_ENABLE_TESTS=OFF;${launcher}")
  run("${CMAKE_COMMAND};--build;${BUILD};-j2")
endif()
run("${CMAKE_COMMAND};--install;${BUILD};--prefix;${prefix}")
if(SHARED_FROM)
  foreach(lib tfeti tfeti_plasticity tfeti_contact)
    file(GLOB found ${prefix}/lib*/lib${lib}.so)
    if(NOT found)
      message(FATAL_ERROR "the shared build installed no lib${lib}.so under ${prefix}")
    endif()
  endforeach()
  file(REMOVE_RECURSE ${BUILD})
  run("${prefix}/bin/tfeti_contact;--print-parameters")
endif()
set(projects consumer tfeti_only)
set(consumer_src ${SOURCE})
set(tfeti_only_src ${TFETI_SOURCE})
if(GUIDE_SOURCE)
  list(APPEND projects guide)
  set(guide_src ${GUIDE_SOURCE})
endif()
foreach(project ${projects})
  set(bin ${WORK}/${project})
  run("${CMAKE_COMMAND};-S;${${project}_src};-B;${bin};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release;${launcher}")
  run("${CMAKE_COMMAND};--build;${bin};--verbose")
  foreach(flag ${FLAGS})
    string(FIND "${out}" "${flag}" at)
    if(at LESS 0)
      message(FATAL_ERROR "${project}: the build does not pass ${flag}:\n${out}")
    endif()
  endforeach()
  if(NOT project STREQUAL "guide")
    run("${bin}/${project}")
    message("${out}")
  elseif(GUIDE_RUN)
    foreach(program own_subdomains mprgp_obstacle contact_cylinders)
      run("${GUIDE_RUN};${bin}/${program};${GUIDE_ARGS_${program}}")
      message("${out}")
    endforeach()
  endif()
endforeach()
