# Embeds kernels/*.cl and kernels/*.h into the binary as raw strings, so phongcl runs from any directory.
# PHONGCL_KERNEL_DIR at run time overrides them with the files on disk (for kernel development).
file(GLOB PHONGCL_KERNEL_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/kernels/*.cl ${PROJECT_SOURCE_DIR}/kernels/*.h)
# A CMake list holds ';', which the shell would split: pass the file list '|'-separated.
string(REPLACE ";" "|" PHONGCL_KERNEL_FILE_ARG "${PHONGCL_KERNEL_FILES}")
set(PHONGCL_EMBEDDED_CPP ${PROJECT_BINARY_DIR}/generated/embedded_kernels.cpp)
add_custom_command(
  OUTPUT ${PHONGCL_EMBEDDED_CPP}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${PHONGCL_EMBEDDED_CPP} "-DFILES=${PHONGCL_KERNEL_FILE_ARG}"
          -P ${PROJECT_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
  DEPENDS ${PHONGCL_KERNEL_FILES} ${PROJECT_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
  COMMENT "Embedding OpenCL kernels"
  VERBATIM)
add_library(phongcl_kernels OBJECT ${PHONGCL_EMBEDDED_CPP})
target_include_directories(phongcl_kernels PUBLIC ${PROJECT_SOURCE_DIR}/host ${PROJECT_SOURCE_DIR})
