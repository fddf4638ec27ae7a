# Embeds web/* (the page `phongcl serve` serves) into the binary, the same way as the kernels, so
# the server runs from any directory with no files beside it.
file(GLOB PHONGCL_WEB_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/web/*.html ${PROJECT_SOURCE_DIR}/web/*.js
     ${PROJECT_SOURCE_DIR}/web/*.css)
string(REPLACE ";" "|" PHONGCL_WEB_FILE_ARG "${PHONGCL_WEB_FILES}")
set(PHONGCL_EMBEDDED_WEB_CPP ${PROJECT_BINARY_DIR}/generated/embedded_web.cpp)
add_custom_command(
  OUTPUT ${PHONGCL_EMBEDDED_WEB_CPP}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${PHONGCL_EMBEDDED_WEB_CPP} "-DFILES=${PHONGCL_WEB_FILE_ARG}"
          -DFUNCTION=embedded_web_files -DHEADER=serve/web_assets.h
          -P ${PROJECT_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
  DEPENDS ${PHONGCL_WEB_FILES} ${PROJECT_SOURCE_DIR}/cmake/WriteEmbeddedKernels.cmake
  COMMENT "Embedding the web page"
  VERBATIM)
