# Polygon and masonry validation cases (doc/validation_polygons.md), included at the end
# of test_cases/validation/CMakeLists.txt. Each case folder holds DATBOX/ (written by its
# gen.py, committed), README.md and check.py. Per run:
#   validation.<name>.run    fracas -q --overwrite [RUN_ARGS] --output <build dir>/<name> <case dir>
#   validation.<name>.check  check.py <build dir>/<name> [CHECK_ARGS]
# fracas_poly_case(<name> <case dir> LABEL quick|long [RUN_ARGS ...] [CHECK_ARGS ...])
function(fracas_poly_case name case_dir)
  cmake_parse_arguments(PC "" "LABEL" "RUN_ARGS;CHECK_ARGS" ${ARGN})
  if(NOT PC_LABEL)
    set(PC_LABEL quick)
  endif()
  set(out ${CMAKE_CURRENT_BINARY_DIR}/poly_${name})
  add_test(NAME validation.${name}.run
           COMMAND ${FRACAS_BIN} -q --overwrite ${FRACAS_NO_RESTARTS} ${PC_RUN_ARGS} --output ${out} ${case_dir})
  add_test(NAME validation.${name}.check
           COMMAND ${FRACAS_CLEAN_AFTER_PASS} ${out} -- ${FRACAS_PYTHON} ${case_dir}/check.py ${out} ${PC_CHECK_ARGS})
  set_tests_properties(validation.${name}.run PROPERTIES
                       FIXTURES_SETUP validation_${name} LABELS "${PC_LABEL};validation;polygons")
  set_tests_properties(validation.${name}.check PROPERTIES
                       FIXTURES_REQUIRED validation_${name} LABELS "${PC_LABEL};validation;polygons")
endfunction()

set(_PV ${CMAKE_CURRENT_SOURCE_DIR})
fracas_poly_case(block_incline ${_PV}/block_incline LABEL quick)
fracas_poly_case(block_incline_theta1 ${_PV}/block_incline LABEL quick
                 RUN_ARGS --set theta=1.0 CHECK_ARGS theta1)
fracas_poly_case(box_tip_slide ${_PV}/box_tip_slide LABEL quick)
fracas_poly_case(arch_heyman ${_PV}/arch_heyman LABEL quick)
fracas_poly_case(tilting_table ${_PV}/tilting_table LABEL quick)
fracas_poly_case(disk_pyramid ${_PV}/disk_pyramid LABEL quick)
fracas_poly_case(disk_roll_polyg ${_PV}/disk_roll_polyg LABEL quick)
