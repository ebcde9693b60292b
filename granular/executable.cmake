# The `granular` executable (owned by the flow work): a thin CLI over
# granular_core. Replicas run as MPI ranks when MPI is found; the same code
# builds without MPI (GRANULAR_HAVE_MPI undefined) and then runs replicas in
# threads (--np).
add_executable(granular src/main.cpp)
target_link_libraries(granular PRIVATE granular_core CLI11::CLI11 nlohmann_json::nlohmann_json project_warnings)
if(MPI_FOUND)
  target_link_libraries(granular PRIVATE MPI::MPI_CXX)
  target_compile_definitions(granular PRIVATE GRANULAR_HAVE_MPI=1)
endif()
set_target_properties(granular PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin)
