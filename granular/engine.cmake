# Engine sources (owned by the engine work): list them in GRANULAR_ENGINE_SOURCES.
file(GLOB GRANULAR_ENGINE_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/engine/*.cpp)
