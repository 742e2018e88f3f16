# Runs Doxygen and fails on any warning, printing them: the manual must build without a single one.
#   cmake -DDOXYGEN=... -DDOXYFILE=... -DWARNING_LOG=... -P run_doxygen.cmake
file(REMOVE ${WARNING_LOG})
get_filename_component(work_dir ${DOXYFILE} DIRECTORY)
execute_process(COMMAND ${DOXYGEN} ${DOXYFILE} WORKING_DIRECTORY ${work_dir}
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE errors)
set(warnings "")
if(EXISTS ${WARNING_LOG})
  file(READ ${WARNING_LOG} warnings)
endif()
string(STRIP "${warnings}" warnings)
if(NOT status EQUAL 0 OR NOT warnings STREQUAL "")
  message(FATAL_ERROR "Doxygen failed (exit ${status}) or warned:\n${warnings}\n${errors}")
endif()
get_filename_component(index ${work_dir}/html/index.html ABSOLUTE)
if(NOT EXISTS ${index})
  message(FATAL_ERROR "Doxygen wrote no ${index}")
endif()
message(STATUS "Manual without warnings: ${index}")
