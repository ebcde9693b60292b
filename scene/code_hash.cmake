# Writes OUT (a header) with a hash of every source file, template and build
# file of the project, so a stage's cache fingerprint changes whenever the
# code that produced it does, committed or not. The header is rewritten only
# when the hash changes, so unchanged code recompiles nothing.
file(GLOB_RECURSE files LIST_DIRECTORIES false
  "${ROOT}/scene/*" "${ROOT}/granular/*" "${ROOT}/shockfit/*" "${ROOT}/meshgen/*"
  "${ROOT}/cfd_cases/*" "${ROOT}/pipeline/*.cpp" "${ROOT}/pipeline/*.hpp" "${ROOT}/CMakeLists.txt")
list(SORT files)
set(all "")
foreach(f IN LISTS files)
  file(SHA256 "${f}" h)
  file(RELATIVE_PATH rel "${ROOT}" "${f}")
  string(APPEND all "${rel}:${h}\n")
endforeach()
string(SHA256 digest "${all}")
string(SUBSTRING "${digest}" 0 12 short)
set(text "#pragma once\nnamespace scene {\ninline constexpr const char* kCodeHash = \"${short}\";\n}\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
