# The Verilator harness: pst_top verilated once per profile (prefix Vpst_top_<profile>) into
# one library, pst_rtl, with makeRtlModel(name) choosing among them.
# Every rtl/**/*.sv, subfolders included: the assertion and cover checkers of rtl/sva/
# (attached by `bind`; never synthesized) among them.
file(GLOB_RECURSE PST_RTL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/rtl/*.sv)

set(PST_RTL_REGISTRY_DECLS "")
set(PST_RTL_REGISTRY_ENTRIES "")
set(PST_RTL_GEN_SOURCES "")
foreach(p ${PST_ALL_PROFILES})
  set(PST_P ${p})
  configure_file(${CMAKE_CURRENT_SOURCE_DIR}/rtl_model_profile.cpp.in
                 ${CMAKE_CURRENT_BINARY_DIR}/rtl_model_${p}.cpp @ONLY)
  list(APPEND PST_RTL_GEN_SOURCES ${CMAKE_CURRENT_BINARY_DIR}/rtl_model_${p}.cpp)
  # The profile file relative to the source tree (resolved at run time: model/source_dir.cpp);
  # a file outside it (an extra profile directory elsewhere) as given.
  file(RELATIVE_PATH file ${PROJECT_SOURCE_DIR} ${PST_PROFILE_FILE_${p}})
  if(file MATCHES "^\\.\\./")
    set(file ${PST_PROFILE_FILE_${p}})
  endif()
  set(asserted false)
  if(p IN_LIST PST_ASSERT_PROFILES)
    set(asserted true)
  endif()
  string(APPEND PST_RTL_REGISTRY_DECLS "std::unique_ptr<RtlModel> makeRtlModel_${p}(const Profile&, const SimOptions&);\n")
  string(APPEND PST_RTL_REGISTRY_ENTRIES "    {\"${p}\", \"${file}\", makeRtlModel_${p}, ${asserted}},\n")
endforeach()
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/rtl_registry.cpp.in ${CMAKE_CURRENT_BINARY_DIR}/rtl_registry.cpp @ONLY)

add_library(pst_rtl STATIC ${PST_RTL_GEN_SOURCES} ${CMAKE_CURRENT_BINARY_DIR}/rtl_registry.cpp)
target_include_directories(pst_rtl PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(pst_rtl PUBLIC pst_golden)
# pst_mul_booth's simulation form (one `*` for the Booth rows; full simulates about 11x faster)
# in the named and test profiles, for whose every multiplier width scripts/mul_proof.py proves
# the two forms equal (ctest mul_proof); extra profiles (sweep points) keep the synthesis form.
# The unit tests (sim/unit) always verilate the synthesis form against the golden model.
option(PST_SIM_MUL "Verilate the named and test profiles with pst_mul_booth's proven simulation form" ON)
foreach(p ${PST_ALL_PROFILES})
  set(defines "")
  get_filename_component(dir ${PST_PROFILE_FILE_${p}} DIRECTORY)
  if(PST_SIM_MUL AND (dir STREQUAL "${PROJECT_SOURCE_DIR}/rtl/configs" OR dir STREQUAL "${PROJECT_SOURCE_DIR}/sim/test_profiles"))
    set(defines PST_MUL_BEHAVIOURAL)
  endif()
  # 8 fast and 8 slow unity files: full's C++ in 16 compile jobs; a small profile fills one or
  # two of them (sim/tools/verilate.py --min-bytes)
  set(flavour "")
  if(NOT p IN_LIST PST_ASSERT_PROFILES)
    set(flavour NO_ASSERT)
  endif()
  if(p IN_LIST PST_GATELEVEL_PROFILES)
    pst_verilate(pst_rtl TOP pst_top PROFILE ${p} PREFIX Vpst_top_${p} SLOTS 8 GATELEVEL NO_ASSERT NO_COVERAGE
                 SOURCES ${PST_GATELEVEL_DIR}/osu018_cells.v ${PST_GATELEVEL_DIR}/${p}.v)
    continue()
  endif()
  pst_verilate(pst_rtl TOP pst_top PROFILE ${p} PREFIX Vpst_top_${p} SLOTS 8 SOURCES ${PST_RTL_SOURCES}
               DEFINES ${defines} ${flavour})
endforeach()
