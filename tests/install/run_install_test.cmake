# Installs hkf into a scratch prefix, then builds and runs a consumer with
# find_package(hkf) and another with pkg-config - the latter after the prefix
# has been moved elsewhere (the installed files are relocatable). libhkf is
# also built as a consumer would with each compiler here (gcc, clang): no
# -Werror reaches it, and it builds. Run with cmake -P.
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})

# A build tree configured as a consumer would: its rules must not turn warnings into errors.
function(check_no_werror dir)
  file(GLOB_RECURSE build_rules ${dir}/build.ninja ${dir}/flags.make)
  if(NOT build_rules)
    message(FATAL_ERROR "no build rules found in ${dir} to check for -Werror")
  endif()
  foreach(file ${build_rules})
    file(READ ${file} rules)
    string(FIND "${rules}" "-Werror" werror)
    if(NOT werror EQUAL -1)
      message(FATAL_ERROR "-Werror reaches a consumer's build of hkf (${file})")
    endif()
  endforeach()
endfunction()

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGV}\n${output}")
  endif()
  message(STATUS "${output}")
endfunction()

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/hkf -G ${GENERATOR} -DCMAKE_INSTALL_PREFIX=${prefix}
    -DHKF_BUILD_TESTS=OFF -DHKF_BUILD_TOOLS=OFF)
check_no_werror(${WORK_DIR}/hkf)  # configured as a consumer would (no options): warnings are not errors there
run(${CMAKE_COMMAND} --build ${WORK_DIR}/hkf)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/hkf)

run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${WORK_DIR}/consumer -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
run(${WORK_DIR}/consumer/consumer)

file(RENAME ${prefix} ${WORK_DIR}/moved)
set(prefix ${WORK_DIR}/moved)
file(GLOB pc_dirs ${prefix}/lib*/pkgconfig ${prefix}/lib/*/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "${pc_dirs}")
execute_process(COMMAND pkg-config --cflags --libs hkf OUTPUT_VARIABLE flags RESULT_VARIABLE result
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pkg-config does not find hkf in ${pc_dirs}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(cc -std=c99 -o ${WORK_DIR}/consumer_pc ${SOURCE_DIR}/tests/install/consumer/consumer.c ${flags})
run(${WORK_DIR}/consumer_pc)

# a consumer's own build of libhkf with each compiler, as shared library too: no -Werror, and it builds
foreach(compiler gcc clang)
  find_program(cc_path ${compiler} NO_CACHE)
  if(NOT cc_path)
    message(STATUS "${compiler} not here: its consumer build skipped")
    continue()
  endif()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/with_${compiler} -G ${GENERATOR} -DCMAKE_C_COMPILER=${cc_path}
      -DHKF_BUILD_TESTS=OFF -DHKF_BUILD_TOOLS=OFF -DBUILD_SHARED_LIBS=ON)
  check_no_werror(${WORK_DIR}/with_${compiler})
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/with_${compiler})
  file(GLOB soname ${WORK_DIR}/with_${compiler}/libhkf/libhkf.so.0)
  if(NOT soname)
    message(FATAL_ERROR "the shared libhkf has no SOVERSION link libhkf.so.0 (${compiler})")
  endif()
endforeach()
