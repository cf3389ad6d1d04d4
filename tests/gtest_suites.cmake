# Run as a POST_BUILD step (cmake -P) for a GoogleTest executable: lists its tests and writes
# CTEST_FILE with one ctest test per test suite (--gtest_filter=Suite.*), so that the cases of a
# suite share one process and what it loads once (the lathe's meshes: about 0.7 s per process in
# Release, several seconds under the sanitizers). Variables: TEST_EXECUTABLE, TEST_WORKING_DIR,
# TEST_ENVIRONMENT, CTEST_FILE, TEST_DISCOVERY_TIMEOUT.

execute_process(
  COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
  WORKING_DIRECTORY "${TEST_WORKING_DIR}"
  TIMEOUT ${TEST_DISCOVERY_TIMEOUT}
  OUTPUT_VARIABLE listing
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${result}):\n${listing}")
endif()

# A parameter printed with an unmatched "[" would stop CMake splitting the list there.
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "[" "<" listing "${listing}")
string(REPLACE "]" ">" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(content "")
foreach(line IN LISTS lines)
  # Suites start in column 0 ("Suite." or "Prefix/Suite.  # TypeParam = ..."); cases are indented.
  if(line MATCHES "^([^ #][^ ]*)\\.")
    set(suite "${CMAKE_MATCH_1}")
    string(APPEND content
      "add_test([==[${suite}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${suite}.*]==])\n"
      "set_tests_properties([==[${suite}]==] PROPERTIES WORKING_DIRECTORY [==[${TEST_WORKING_DIR}]==]"
      " ENVIRONMENT [==[${TEST_ENVIRONMENT}]==])\n")
  endif()
endforeach()
file(WRITE "${CTEST_FILE}" "${content}")
