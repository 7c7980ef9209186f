# Cohesive zone validation cases (doc/czm.md), included from CMakeLists.txt.
# Each case folder holds gen.py (writes the committed DATBOX), README.md and check.py.
#   validation.czm_<case>.run    fracas --overwrite --output <build dir>/czm_<case> <deck>
#   validation.czm_<case>.check  check.py <build dir>/czm_<case> [args] (fixture of the run)
# LABEL is quick (run and check a few seconds each), medium (up to ~20 s) or long.
function(fracas_czm_case name deck_dir check_script label)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/czm_${name})
  add_test(NAME validation.czm_${name}.run
           COMMAND ${FRACAS_BIN} -q --overwrite ${FRACAS_NO_RESTARTS} ${czm_run_args} --output ${out} ${deck_dir})
  add_test(NAME validation.czm_${name}.check
           COMMAND ${FRACAS_CLEAN_AFTER_PASS} ${out} -- ${FRACAS_PYTHON} ${check_script} ${out} ${ARGN})
  set_tests_properties(validation.czm_${name}.run PROPERTIES
                       FIXTURES_SETUP validation_czm_${name} LABELS "${label};validation;czm")
  set_tests_properties(validation.czm_${name}.check PROPERTIES
                       FIXTURES_REQUIRED validation_czm_${name} LABELS "${label};validation;czm")
endfunction()

set(_czm ${CMAKE_CURRENT_SOURCE_DIR})
# Mode I: traction-opening curve, peak and fracture energy of each law, with LMGC90's
# damage solved within the step (the default) and with LMGC90's explicit update (its
# one-step lag).
set(czm_run_args "")
foreach(law mac mp3 mal th expo abp)
  fracas_czm_case(mode_I_${law} ${_czm}/czm_mode_I/${law} ${_czm}/czm_mode_I/check.py quick ${law})
endforeach()
set(czm_run_args --set cohesive_damage=explicit)
foreach(law mac mp3 mal th expo abp)
  fracas_czm_case(mode_I_${law}_explicit ${_czm}/czm_mode_I/${law} ${_czm}/czm_mode_I/check.py quick ${law})
endforeach()
set(czm_run_args "")
# Energy of a crack against the opening per step (1, 10, 100 softening lengths), every law:
# the damage energy and the interface's work equal the law's energy within 2 % (doc/czm.md).
add_test(NAME validation.czm_step_size
         COMMAND ${FRACAS_PYTHON} ${_czm}/czm_step_size/study.py ${FRACAS_BIN} ${CMAKE_CURRENT_BINARY_DIR}/czm_step_size)
set_tests_properties(validation.czm_step_size PROPERTIES LABELS "quick;validation;czm")
# Time-step control for cracks (crack_step_limit): increments bounded, steps cut and grown
# back on the run's time grid, energies of both schemes against the law's.
add_test(NAME validation.crack_step_control
         COMMAND ${FRACAS_PYTHON} ${_czm}/crack_step_control/check.py ${FRACAS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/crack_step_control)
set_tests_properties(validation.crack_step_control PROPERTIES LABELS "quick;validation;czm")
# Mode II under a compressive preload: cohesive shear, then Coulomb friction mu p.
foreach(law mac expo)
  fracas_czm_case(mode_II_${law} ${_czm}/czm_mode_II/${law} ${_czm}/czm_mode_II/check.py quick ${law})
endforeach()
# Cyclic opening: secant unloading (beta frozen), damage resumed past the old maximum.
foreach(law mac mp3)
  fracas_czm_case(cyclic_${law} ${_czm}/czm_cyclic/${law} ${_czm}/czm_cyclic/check.py medium ${law})
endforeach()
set(czm_run_args --set cohesive_damage=explicit)
foreach(law mac mp3)
  fracas_czm_case(cyclic_${law}_explicit ${_czm}/czm_cyclic/${law} ${_czm}/czm_cyclic/check.py medium ${law})
endforeach()
set(czm_run_args "")
# Rate dependence of the viscous MAC law (b > 0): peaks vs the integrated damage ODE.
# Its check replicates LMGC90's implicit Euler of the damage ODE after the step: run
# with LMGC90's explicit update.
set(czm_run_args --set cohesive_damage=explicit)
fracas_czm_case(rate ${_czm}/czm_rate ${_czm}/czm_rate/check.py quick)
set(czm_run_args "")
# Energy audit: a glued block pushed until the glue breaks, then sliding with friction.
fracas_czm_case(energy ${_czm}/czm_energy ${_czm}/czm_energy/check.py medium)
# Both blocks fully driven: the contacts exist and follow the law's closed form (issue 9).
set(czm_run_args --set cohesive_damage=explicit)   # its reference: LMGC90's update, step by step
fracas_czm_case(driven_pair ${_czm}/czm_driven_pair ${_czm}/czm_driven_pair/check.py quick)
set(czm_run_args "")
# Meshed blocks: the gap law of each family (MAC_CZM, MP3_CZM, MAL_CZM, TH_CZM, EXPO_CZM, ABP_CZM)
# on CLALp contacts between two Q4 MAILx bodies, opened (mode I) or slid (mode II), the
# deck generated into the build tree (gen.py --mesh [--shear]), czm_mode_I's checks.
foreach(mode I II)
  if(mode STREQUAL "II")
    set(flag --shear)
  else()
    set(flag "")
  endif()
  foreach(law mac mp3 mal th expo abp)
    set(name czm_mode_${mode}_mesh_${law})
    set(out ${CMAKE_CURRENT_BINARY_DIR}/${name})
    add_test(NAME validation.${name}.gen
             COMMAND ${FRACAS_PYTHON} ${_czm}/czm_mode_I/gen.py --mesh ${out} ${law} ${flag})
    add_test(NAME validation.${name}.run COMMAND ${FRACAS_BIN} -q --overwrite ${FRACAS_NO_RESTARTS} ${out})
    add_test(NAME validation.${name}.check
             COMMAND ${FRACAS_CLEAN_AFTER_PASS} ${out} --
                     ${FRACAS_PYTHON} ${_czm}/czm_mode_I/check.py ${out} ${law} --mesh ${flag})
    set_tests_properties(validation.${name}.gen PROPERTIES
                         FIXTURES_SETUP ${name}_deck LABELS "quick;validation;czm")
    set_tests_properties(validation.${name}.run PROPERTIES
                         FIXTURES_REQUIRED ${name}_deck FIXTURES_SETUP ${name} LABELS "quick;validation;czm")
    set_tests_properties(validation.${name}.check PROPERTIES
                         FIXTURES_REQUIRED "${name}_deck;${name}" LABELS "quick;validation;czm")
  endforeach()
endforeach()
# The one Python implementation of the laws (fracas_tools.cohesive.Law) against the
# solver, every cohesive law it runs (MAC_CZM, IQS_MAC_CZM, MP3_CZM, (IQS_)MAL_CZM,
# (IQS_)TH_CZM, (IQS_)EXPO_CZM, (IQS_)ABP_CZM), both damage schemes, on a driven pair opened and slid
# (mixed mode, with a partial closing): beta, reactions and energies at every step to
# round-off (czm_law_mirror/README.md), so that a drift of either side is red.
add_test(NAME validation.czm_law_mirror
         COMMAND ${FRACAS_PYTHON} ${_czm}/czm_law_mirror/mirror.py ${FRACAS_BIN} ${CMAKE_CURRENT_BINARY_DIR}/czm_law_mirror)
set_tests_properties(validation.czm_law_mirror PROPERTIES LABELS "medium;validation;czm")
