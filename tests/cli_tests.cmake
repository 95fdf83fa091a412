# Tests of globular_cli: the scene reader and the command, end to end.
globular_test(scene_test SOURCES scene_test.cpp scene_collider_test.cpp scene_thermal_test.cpp LIBS globular_cli)
# End-to-end: runs the built executable, so it must be built first.
globular_test(cli_test SOURCES cli_test.cpp LIBS globular_cli)
add_dependencies(cli_test globular)
target_compile_definitions(cli_test PRIVATE GLOBULAR_TEST_VERSION="${PROJECT_VERSION}"
                           GLOBULAR_TEST_JEMALLOC=$<BOOL:${GLOBULAR_JEMALLOC}>)
globular_test(resume_test SOURCES resume_test.cpp LIBS globular_sim)
add_dependencies(resume_test globular)
# Issue 11's classes of failure, end to end (reads the stages' files back to check them).
globular_test(reliability_test SOURCES reliability_test.cpp
              LIBS globular_surface OpenVDB::openvdb)
add_dependencies(reliability_test globular)
# Houdini's names, types and classes in what `globular run` writes (issue 16).
globular_test(houdini_conventions_test SOURCES houdini_conventions_test.cpp
              LIBS OpenVDB::openvdb)
add_dependencies(houdini_conventions_test globular)
# Issue 17: `globular farm`'s batch scripts (no Slurm needed), and the shot on a local
# one-node Slurm (scripts/local_slurm.sh; skipped where Slurm is not installed).
globular_test(farm_scripts_test SOURCES farm_scripts_test.cpp farm_command_test.cpp
              LIBS globular_cli)
add_test(NAME FarmSlurm.SplitShotMatchesLocalRunAndResubmits
         COMMAND ${PROJECT_SOURCE_DIR}/tests/farm_slurm_test.sh $<TARGET_FILE:globular>)
set_tests_properties(FarmSlurm.SplitShotMatchesLocalRunAndResubmits PROPERTIES
                     LABELS slurm SKIP_RETURN_CODE 77 TIMEOUT 240 RUN_SERIAL TRUE)
