# `phongcl serve` (host/serve/): a front end, like the command line, so it stays out of the product
# library: only the phongcl executable (and its tests) link the HTTP server, the JPEG encoder and the
# embedded page (web/, cmake/EmbedWeb.cmake).
include(cmake/EmbedWeb.cmake)
file(GLOB PHONGCL_SERVE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/host/serve/*.cpp)
add_library(phongcl_serve STATIC ${PHONGCL_SERVE_SOURCES} ${PHONGCL_EMBEDDED_WEB_CPP})
target_link_libraries(phongcl_serve PUBLIC phongcl_internal Boost::headers Threads::Threads
                                    PRIVATE libjpeg-turbo::turbojpeg)
# Beast's string_view as std::string_view, so the serve code passes text between Beast and itself as is.
target_compile_definitions(phongcl_serve PUBLIC BOOST_BEAST_USE_STD_STRING_VIEW)
target_link_libraries(phongcl PRIVATE phongcl_serve)
