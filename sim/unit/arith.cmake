# Unit tests of the arithmetic stages (pst_quadric, pst_quadric_fold, pst_octave_term, pst_filter_width,
# pst_isqrt) against the golden model (model/golden/arith_fx.cpp), one verilated top per
# profile. Seed: PST_SEED=<n> in the environment replays a run (the test prints its seed).
set(PST_ARITH_UNIT_PARAMS
    CoordInt,CoordFrac,QuadricInt,QuadricFrac,NoiseOutFrac,AmplitudeInt,AmplitudeFrac,GradMatrixInt,GradMatrixFrac,JacobianInt,JacobianFrac,Log2Clut,WidthFrac,FilterNorm,FInt,FFrac,GradInt,GradFrac,OctaveRegs)
# The top and the modules under test; what they instantiate Verilator finds in rtl/ (-y).
set(PST_ARITH_UNIT_SOURCES ${PROJECT_SOURCE_DIR}/sim/unit/pst_arith_unit_top.sv ${PROJECT_SOURCE_DIR}/rtl/octave/pst_quadric.sv
    ${PROJECT_SOURCE_DIR}/rtl/octave/pst_quadric_fold.sv     ${PROJECT_SOURCE_DIR}/rtl/octave/pst_quadric_serial.sv ${PROJECT_SOURCE_DIR}/rtl/octave/pst_octave_term.sv
    ${PROJECT_SOURCE_DIR}/rtl/width/pst_filter_width.sv ${PROJECT_SOURCE_DIR}/rtl/common/pst_isqrt.sv)
pst_unit_tests(arith_unit TOP pst_arith_unit_top PARAMS ${PST_ARITH_UNIT_PARAMS} SOURCES ${PST_ARITH_UNIT_SOURCES})
