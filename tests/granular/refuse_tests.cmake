# Refusals, inelastic collapse and results kept on interrupt (executable).
add_stage_test(NAME granular_refuse_tests PREFIX granular
  SOURCES refuse_test.cpp
  LIBS nlohmann_json::nlohmann_json test_support
  LABELS fast TIMEOUT 120)
add_dependencies(granular_refuse_tests granular)
