# Flow tests (supersonic stream past a body, fields, CLI). Fast ones run in
# a few seconds each on small bodies; the shock-angle check is `slow`.
add_stage_test(NAME granular_flow_tests PREFIX granular
  SOURCES flow_setup_test.cpp flow_fields_test.cpp flow_steady_state_test.cpp precision_stop_test.cpp
  LIBS granular_core
  LABELS fast TIMEOUT 60)
# The steady-state rule is private to granular_core (src/flow).
target_include_directories(granular_flow_tests PRIVATE ${PROJECT_SOURCE_DIR}/granular/src/flow)
add_stage_test(NAME granular_flow_run_tests PREFIX granular
  SOURCES flow_run_test.cpp flow_precision_test.cpp flow_hard_cases_test.cpp flow_cli_test.cpp flow_support.cpp
  LIBS granular_core
  LABELS fast TIMEOUT 120)
add_dependencies(granular_flow_run_tests granular)
add_stage_test(NAME granular_flow_slow_tests PREFIX granular
  SOURCES flow_shock_test.cpp flow_support.cpp
  LIBS granular_core
  LABELS slow TIMEOUT 600)
add_dependencies(granular_flow_slow_tests granular)
