# Unit test of the colour-table filter (rtl/colour/pst_clut_filter.sv) against the golden model
# (model/golden/clut_filter_fx.cpp): random tables through the write port, then random and
# special (f, W, clamp, kind) vectors, every output bit compared. One verilated top per
# profile. Seed: PST_SEED=<n> in the environment replays a run (the test prints its seed);
# PST_CLUT_VECTORS=<n> changes the vector count per table (default 40000; 3 tables).
set(PST_CLUT_UNIT_PARAMS FInt,FFrac,Log2Clut,ColourBits,WidthFrac,FilterRecipFrac,Datapath)
set(PST_CLUT_UNIT_SOURCES ${PROJECT_SOURCE_DIR}/rtl/colour/pst_clut_filter.sv
    ${PROJECT_SOURCE_DIR}/rtl/colour/pst_clut_channel.sv ${PROJECT_SOURCE_DIR}/rtl/common/pst_delay.sv)
foreach(p ${PST_PROFILES})
  add_executable(clut_unit_${p} ${PROJECT_SOURCE_DIR}/sim/unit/clut_unit_test.cpp)
  target_link_libraries(clut_unit_${p} PRIVATE pst_golden GTest::gtest_main)
  target_compile_definitions(clut_unit_${p} PRIVATE PST_PROFILE_PATH="${PROJECT_SOURCE_DIR}/rtl/configs/${p}.toml")
  pst_verilate(clut_unit_${p} TOP pst_clut_filter PROFILE ${p} PARAMS ${PST_CLUT_UNIT_PARAMS}
               SOURCES ${PST_CLUT_UNIT_SOURCES})
  gtest_discover_tests(clut_unit_${p} TEST_PREFIX "${p}." DISCOVERY_TIMEOUT 60)
endforeach()
