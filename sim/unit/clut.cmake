# Unit test of the colour-table filter (rtl/colour/pst_clut_filter.sv) against the golden model
# (model/golden/clut_filter_fx.cpp): random tables through the write port, then random and
# special (f, W, clamp, kind) vectors, every output bit compared. One verilated top per
# profile. Seed: PST_SEED=<n> in the environment replays a run (the test prints its seed);
# PST_CLUT_VECTORS=<n> changes the vector count per table (default 4000, 40000 under ctest -L long; 3 tables).
set(PST_CLUT_UNIT_PARAMS FInt,FFrac,Log2Clut,ColourBits,WidthFrac,FilterRecipFrac,Datapath)
set(PST_CLUT_UNIT_SOURCES ${PROJECT_SOURCE_DIR}/rtl/colour/pst_clut_filter.sv)
pst_unit_tests(clut_unit TOP pst_clut_filter PARAMS ${PST_CLUT_UNIT_PARAMS} SOURCES ${PST_CLUT_UNIT_SOURCES})
