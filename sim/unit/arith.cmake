# Unit tests of the arithmetic stages (pst_quadric, pst_octave_term, pst_filter_width,
# pst_isqrt) against the golden model (model/golden/arith_fx.cpp), one verilated top per
# profile. Seed: PST_SEED=<n> in the environment replays a run (the test prints its seed).
set(PST_ARITH_UNIT_PARAMS
    CoordInt,CoordFrac,QuadricInt,QuadricFrac,NoiseOutFrac,AmplitudeInt,AmplitudeFrac,GradMatrixInt,GradMatrixFrac,JacobianInt,JacobianFrac,Log2Clut,WidthFrac,FilterNorm,FInt,FFrac,GradInt,GradFrac,OctaveRegs)
set(PST_ARITH_UNIT_SOURCES
    ${PROJECT_SOURCE_DIR}/sim/unit/pst_arith_unit_top.sv
    ${PROJECT_SOURCE_DIR}/rtl/octave/pst_quadric.sv
    ${PROJECT_SOURCE_DIR}/rtl/octave/pst_quadric_serial.sv
    ${PROJECT_SOURCE_DIR}/rtl/octave/pst_octave_term.sv
    ${PROJECT_SOURCE_DIR}/rtl/width/pst_filter_width.sv
    ${PROJECT_SOURCE_DIR}/rtl/common/pst_isqrt.sv
    ${PROJECT_SOURCE_DIR}/rtl/common/pst_floor_sat.sv
    ${PROJECT_SOURCE_DIR}/rtl/common/pst_delay.sv)
foreach(p ${PST_PROFILES})
  add_executable(arith_unit_${p} ${PROJECT_SOURCE_DIR}/sim/unit/arith_unit_test.cpp)
  target_link_libraries(arith_unit_${p} PRIVATE pst_golden GTest::gtest_main)
  target_include_directories(arith_unit_${p} PRIVATE ${PROJECT_SOURCE_DIR}/sim)
  target_compile_definitions(arith_unit_${p} PRIVATE PST_PROFILE_PATH="${PROJECT_SOURCE_DIR}/rtl/configs/${p}.toml")
  pst_verilate(arith_unit_${p} TOP pst_arith_unit_top PROFILE ${p} PARAMS ${PST_ARITH_UNIT_PARAMS}
               SOURCES ${PST_ARITH_UNIT_SOURCES})
  gtest_discover_tests(arith_unit_${p} TEST_PREFIX "${p}." DISCOVERY_TIMEOUT 60)
endforeach()
