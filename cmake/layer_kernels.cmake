# hkf_layer_kernels(OUT): the estimator's layer loops, one file per instruction-set level, each built for its
# level alone (estimator/src/models/kernels/layer_kernels_impl.hpp); simd_level.cpp takes the best the CPU runs.
# Multiply-adds are contracted (an FMA where the level has one) and strict aliasing is kept, as for
# fast_layers.cpp. Source properties belong to the folder that calls this, so each target's folder calls it.
function(hkf_layer_kernels out)
  set(dir ${PROJECT_SOURCE_DIR}/estimator/src/models/kernels)
  set(flags -fstrict-aliasing -ffp-contract=fast)
  set(sources ${dir}/layer_kernels_baseline.cpp)
  set_source_files_properties(${dir}/layer_kernels_baseline.cpp PROPERTIES COMPILE_OPTIONS "${flags}")
  if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
    list(APPEND sources ${dir}/layer_kernels_avx.cpp ${dir}/layer_kernels_avx2.cpp ${dir}/layer_kernels_avx512.cpp)
    set_source_files_properties(${dir}/layer_kernels_avx.cpp PROPERTIES COMPILE_OPTIONS "${flags};-mavx")
    set_source_files_properties(${dir}/layer_kernels_avx2.cpp PROPERTIES COMPILE_OPTIONS "${flags};-mavx2;-mfma")
    set_source_files_properties(${dir}/layer_kernels_avx512.cpp PROPERTIES
      COMPILE_OPTIONS "${flags};-mavx512f;-mfma;-mprefer-vector-width=512")
  endif()
  set(${out} ${sources} PARENT_SCOPE)
endfunction()
