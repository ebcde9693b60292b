# Engine tests (event-driven hard-disk engine): fast ones run in every CI
# job; the 10^7-collision wedge-tip overlap test is labelled slow.
add_stage_test(NAME granular_engine_tests PREFIX granular
  SOURCES engine_support.cpp engine_contact_test.cpp engine_surface_test.cpp
          engine_conservation_test.cpp engine_eos_test.cpp engine_haff_test.cpp
          engine_box_run_test.cpp engine_checkpoint_test.cpp engine_flow_test.cpp
          engine_calendar_test.cpp engine_grid_test.cpp engine_drift_test.cpp
  LIBS granular_core LABELS fast TIMEOUT 120)
# The calendar is internal to the engine; its test reads the private header.
target_include_directories(granular_engine_tests PRIVATE ${PROJECT_SOURCE_DIR}/granular/src/engine)
add_stage_test(NAME granular_engine_slow_tests PREFIX granular
  SOURCES engine_support.cpp engine_slow_test.cpp
  LIBS granular_core LABELS slow TIMEOUT 1200)
# The look-ahead prefetch stages are in the optimised binary (an x86-64
# disassembly check; Debug builds inline nothing and are not checked).
find_program(OBJDUMP_EXE objdump)
if(OBJDUMP_EXE AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64"
   AND CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$")
  add_test(NAME granular.Build.LookAheadStagesAreCompiledIn
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/look_ahead_in_binary.sh ${OBJDUMP_EXE}
            $<TARGET_FILE:granular_core>)
  set_tests_properties(granular.Build.LookAheadStagesAreCompiledIn PROPERTIES LABELS fast TIMEOUT 60)
endif()
