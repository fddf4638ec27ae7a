# `phongcl serve` (host/serve/): a front end, like the command line, so it stays out of the product
# library: only the phongcl executable (and its test) link the HTTP server, the JPEG encoder and the
# embedded page (web/, cmake/EmbedWeb.cmake).
include(cmake/EmbedWeb.cmake)
file(GLOB PHONGCL_SERVE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/host/serve/*.cpp)
add_library(phongcl_serve STATIC ${PHONGCL_SERVE_SOURCES} ${PHONGCL_EMBEDDED_WEB_CPP})
target_link_libraries(phongcl_serve PUBLIC phongcl_internal PkgConfig::HTTPLIB PRIVATE libjpeg-turbo::turbojpeg)
target_link_libraries(phongcl PRIVATE phongcl_serve)
