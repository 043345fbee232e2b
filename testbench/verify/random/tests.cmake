# Constrained-random regression (testbench/verify/random), included after sim/ (it needs the list of
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

# scripts/regress.py, the sharded regression: 40k random fragments in shards on two local workers
# with one shard killed while it runs (re-run alone; merged = one process's run), an RTL
# assertion in one shard (merged as the first failure, its replay fails alone), scene shards.
# The same on a one-node SLURM cluster (scripts/slurm_local.sh) under label slurm.
# On a profile verilated with its assertions (the test profiles are; serial_short is reduced's
# structure with fewer octaves).
if("serial_short" IN_LIST PST_ASSERT_PROFILES)
  set(PST_SHARD_PROFILE serial_short)
elseif(PST_ASSERT_PROFILES)
  list(GET PST_ASSERT_PROFILES 0 PST_SHARD_PROFILE)
else()
  set(PST_SHARD_PROFILE "")
  message(STATUS "regress_shards tests left out: no profile of this build is verilated with assertions (keep a test profile or -DPST_SIM_ASSERT=ON)")
endif()
if(PST_SHARD_PROFILE)
  add_test(NAME regress_shards_local
           COMMAND ${PROJECT_SOURCE_DIR}/scripts/tests/regress_shards_test.sh ${PROJECT_BINARY_DIR}/regress_shards_local
                   $<TARGET_FILE:pst> ${PST_SHARD_PROFILE} local)
  set_tests_properties(regress_shards_local PROPERTIES LABELS python TIMEOUT 300)
  add_test(NAME regress_shards_slurm
           COMMAND ${PROJECT_SOURCE_DIR}/scripts/tests/regress_shards_test.sh ${PROJECT_BINARY_DIR}/regress_shards_slurm
                   $<TARGET_FILE:pst> ${PST_SHARD_PROFILE} slurm)
  set_tests_properties(regress_shards_slurm PROPERTIES LABELS slurm TIMEOUT 900 RUN_SERIAL TRUE)
endif()
