# penumbra_add_gtest_groups(TARGET GROUP_SIZE N LABELS L [TIMEOUT S] [CHECKED REGEX] [ENVIRONMENT VAR=VALUE...])
# Registers the tests of a GoogleTest program with ctest in groups of at most N tests of one suite,
# each group one process (`ctest -N` lists them as Suite.group-K; the output of a failed group names
# its failed tests). The render tests share one Vulkan device and its compiled pipelines per process,
# and creating both costs more on lavapipe than most tests do, so a process per group instead of a
# process per test cuts the suite's time several-fold. The groups are found when ctest starts (the
# program lists its tests), like gtest_discover_tests' PRE_TEST mode. Tests whose Suite.Test name
# matches CHECKED form groups of their own with the extra label "checked".
set(PENUMBRA_GTEST_GROUPS_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/gtest_groups_discover.cmake")

function(penumbra_add_gtest_groups target)
  cmake_parse_arguments(ARG "" "GROUP_SIZE;LABELS;TIMEOUT;CHECKED" "ENVIRONMENT" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  list(JOIN ARG_ENVIRONMENT "|" environment)  # a list again in the discovery script
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_groups.cmake")
  file(GENERATE OUTPUT "${include_file}" CONTENT
"set(PENUMBRA_GROUPS_EXE \"$<TARGET_FILE:${target}>\")
set(PENUMBRA_GROUPS_SIZE ${ARG_GROUP_SIZE})
set(PENUMBRA_GROUPS_LABELS \"${ARG_LABELS}\")
set(PENUMBRA_GROUPS_TIMEOUT ${ARG_TIMEOUT})
set(PENUMBRA_GROUPS_ENVIRONMENT \"${environment}\")
set(PENUMBRA_GROUPS_CHECKED [==[${ARG_CHECKED}]==])
include(\"${PENUMBRA_GTEST_GROUPS_SCRIPT}\")
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
