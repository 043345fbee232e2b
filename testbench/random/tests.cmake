# Constrained-random regression (testbench/random), included after sim/ (it needs the list of
# verilated profiles): PST_RANDOM_FRAGMENTS random fragments per verilated profile in the test
# suite (ctest label `random`). The long run (README "Verification") is the same command with
# --random 10000000.
set(PST_RANDOM_FRAGMENTS 100000 CACHE STRING "Random fragments per profile in the test suite")
foreach(p ${PST_ALL_PROFILES})
  add_test(NAME random_regress_${p}
           COMMAND pst regress --random ${PST_RANDOM_FRAGMENTS} --seed 1 --profile ${p})
  set_tests_properties(random_regress_${p} PROPERTIES LABELS random
                       ENVIRONMENT "PST_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endforeach()
