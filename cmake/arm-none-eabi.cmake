# cmake/arm-none-eabi.cmake - cross-compiling libhkf for a Cortex-M with the
# GNU Arm Embedded toolchain (Debian: gcc-arm-none-eabi, libnewlib-arm-none-eabi).
#   cmake -S . -B build-m4f -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake \
#         -DHKF_CPU=cortex-m4f -DHKF_REAL=float
# HKF_CPU: cortex-m0 (ARMv6-M, no FPU), cortex-m4f (fpv4-sp-d16, hard float),
# cortex-m7 (fpv5-d16: single and double precision in hardware, hard float).
# Only libhkf and the target tests (tests/mcu) are built for a target.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY) # no runtime to link a test program against yet

set(HKF_CPU "cortex-m4f" CACHE STRING "target core: cortex-m0, cortex-m4f or cortex-m7")
set_property(CACHE HKF_CPU PROPERTY STRINGS cortex-m0 cortex-m4f cortex-m7)
if(HKF_CPU STREQUAL "cortex-m0")
  set(HKF_CPU_FLAGS "-mcpu=cortex-m0 -mthumb -mfloat-abi=soft")
elseif(HKF_CPU STREQUAL "cortex-m4f")
  set(HKF_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
elseif(HKF_CPU STREQUAL "cortex-m7")
  set(HKF_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
else()
  message(FATAL_ERROR "HKF_CPU must be cortex-m0, cortex-m4f or cortex-m7, not '${HKF_CPU}'")
endif()
set(CMAKE_C_FLAGS_INIT "${HKF_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${HKF_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
