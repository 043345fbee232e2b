# Unit tests of units 1 and 2 (pst_octave_transform, pst_noise and its sub-modules) against
# the golden model (model/golden/noise_fx.cpp), bit for bit, one verilated top per profile.
# Seed: PST_SEED=<n> in the environment replays a run (the test prints its seed).
set(PST_NOISE_UNIT_PARAMS
    CoordInt,CoordFrac,MatrixInt,MatrixFrac,OffsetInt,OffsetFrac,NoiseLatticeFrac,NoiseInterp,NoiseCorner,NoiseHash,NoiseValueFrac,NoiseOutFrac,NoiseSteps,NoiseGuardBits,NoiseGradFrac)
# The top and the modules under test; their sub-modules Verilator finds in rtl/ (-y).
set(PST_NOISE_UNIT_SOURCES ${PROJECT_SOURCE_DIR}/sim/unit/pst_noise_unit_top.sv
    ${PROJECT_SOURCE_DIR}/rtl/octave/pst_octave_transform.sv ${PROJECT_SOURCE_DIR}/rtl/noise/pst_noise.sv)

pst_unit_tests(noise_unit TOP pst_noise_unit_top PARAMS ${PST_NOISE_UNIT_PARAMS} SOURCES ${PST_NOISE_UNIT_SOURCES})

# Variants: a profile's formats with some noise parameters overridden, so that every
# generate branch of the noise unit is built and compared (the two profiles cover
# scurve/value_gradient/rayshade and linear/value_gradient/perm256 only):
#   var_a  full formats, linear, value corners, perm256, NoiseOutFrac 11 (node frac = VF),
#          two steps per evaluation
#   var_b  reduced formats, scurve, value_gradient, rayshade, NoiseValueFrac 15 (> node frac),
#          the reduced's four steps
#   var_c  reduced formats, scurve, perm256, VF 3, LF 4, OF 10 (VF + LF < node frac), eight
#          steps (one corner per cycle), one guard bit
#   var_d  reduced formats, Perlin 2002 (quintic, grad12, perlin256), the reduced's four steps
#   var_e  full formats, Perlin 2002, one step, one guard bit, LF 17 > node frac (the corner
#          value's floor)
#   var_f  full, derivative lanes floored to 12 fraction bits (noise.grad_frac 12 < node
#          frac 20: corner and lerp floors, narrow own-axis products)
#   var_g  reduced formats, linear, value corners, perm256, eight steps, grad_frac 4 (the
#          linear own-axis term on the floored difference; value corners' zero lanes)
#   var_h  reduced formats, Perlin 2002, grad_frac 5 (grad12 lanes, quintic ds)
# The test applies the same overrides to the loaded profile (PST_NOISE_OVERRIDES).
set(PST_NOISE_VARIANTS
    "var_a|full|NoiseInterp=1,NoiseCorner=1,NoiseHash=1,NoiseOutFrac=11,NoiseSteps=2"
    "var_b|reduced|NoiseInterp=0,NoiseCorner=0,NoiseHash=0,NoiseValueFrac=15"
    "var_c|reduced|NoiseInterp=0,NoiseCorner=0,NoiseHash=1,NoiseValueFrac=3,NoiseLatticeFrac=4,NoiseOutFrac=10,NoiseSteps=8,NoiseGuardBits=1"
    "var_d|reduced|NoiseInterp=2,NoiseCorner=2,NoiseHash=2"
    "var_e|full|NoiseInterp=2,NoiseCorner=2,NoiseHash=2,NoiseGuardBits=1,NoiseLatticeFrac=17,NoiseOutFrac=14"
    "var_f|full|NoiseGradFrac=12"
    "var_g|reduced|NoiseInterp=1,NoiseCorner=1,NoiseHash=1,NoiseSteps=8,NoiseGradFrac=4"
    "var_h|reduced|NoiseInterp=2,NoiseCorner=2,NoiseHash=2,NoiseGradFrac=5")
foreach(v ${PST_NOISE_VARIANTS})
  string(REPLACE "|" ";" v "${v}")
  list(GET v 0 vname)
  list(GET v 1 vprofile)
  list(GET v 2 voverrides)
  set(cfg ${PROJECT_SOURCE_DIR}/rtl/configs/${vprofile}.toml)
  pst_profile_query(plist ${cfg} --list --only ${PST_NOISE_UNIT_PARAMS})
  string(REPLACE "," ";" ovlist "${voverrides}")
  set(gparams "")
  foreach(line ${plist})
    string(REPLACE " " ";" kv "${line}")
    list(GET kv 0 pname)
    list(GET kv 1 pvalue)
    foreach(ov ${ovlist})
      if(ov MATCHES "^${pname}=(.*)$")
        set(pvalue ${CMAKE_MATCH_1})
      endif()
    endforeach()
    list(APPEND gparams -G${pname}=${pvalue})
  endforeach()
  set(target noise_unit_${vname})
  add_executable(${target} ${PROJECT_SOURCE_DIR}/sim/unit/noise_unit_test.cpp)
  target_link_libraries(${target} PRIVATE pst_golden GTest::gtest_main)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/sim)
  target_compile_definitions(${target} PRIVATE PST_PROFILE_PATH="rtl/configs/${vprofile}.toml" PST_NOISE_OVERRIDES="${voverrides}")
  pst_verilate(${target} TOP pst_noise_unit_top GPARAMS ${gparams} NO_TRACE NO_COVERAGE
               DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/${target}_pst_noise_unit_top SOURCES ${PST_NOISE_UNIT_SOURCES})
  gtest_discover_tests(${target} TEST_PREFIX "${vname}." DISCOVERY_TIMEOUT 60)
endforeach()
