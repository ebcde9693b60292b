# Flow / fields sources (owned by the flow work).
file(GLOB GRANULAR_FLOW_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/flow/*.cpp)
