# Tests of globular_cli: the scene reader and the command, end to end.
globular_test(scene_test SOURCES scene_test.cpp scene_collider_test.cpp scene_thermal_test.cpp LIBS globular_cli)
# End-to-end: runs the built executable, so it must be built first.
globular_test(cli_test SOURCES cli_test.cpp LIBS globular_cli)
add_dependencies(cli_test globular)
target_compile_definitions(cli_test PRIVATE GLOBULAR_TEST_VERSION="${PROJECT_VERSION}")
globular_test(resume_test SOURCES resume_test.cpp LIBS globular_sim)
add_dependencies(resume_test globular)
# Issue 11's classes of failure, end to end (reads the stages' files back to check them).
globular_test(reliability_test SOURCES reliability_test.cpp
              LIBS globular_surface OpenVDB::openvdb)
add_dependencies(reliability_test globular)
