# Installs hkf into a scratch prefix, then builds and runs a consumer with
# find_package(hkf) and another with pkg-config - the latter after the prefix
# has been moved elsewhere (the installed files are relocatable). Run with cmake -P.
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGV}\n${output}")
  endif()
  message(STATUS "${output}")
endfunction()

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/hkf -G ${GENERATOR} -DCMAKE_INSTALL_PREFIX=${prefix}
    -DHKF_BUILD_TESTS=OFF -DHKF_BUILD_TOOLS=OFF)
# configured as a consumer would (no options): warnings are not errors there
file(GLOB_RECURSE build_rules ${WORK_DIR}/hkf/build.ninja ${WORK_DIR}/hkf/flags.make)
foreach(file ${build_rules})
  file(READ ${file} rules)
  string(FIND "${rules}" "-Werror" werror)
  if(NOT werror EQUAL -1)
    message(FATAL_ERROR "-Werror reaches a consumer's build of hkf (${file})")
  endif()
endforeach()
if(NOT build_rules)
  message(FATAL_ERROR "no build rules found in ${WORK_DIR}/hkf to check for -Werror")
endif()
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
