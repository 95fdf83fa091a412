# Tests of globular_sim.
globular_test(globule_cache_test SOURCES globule_cache_test.cpp LIBS globular_sim OpenVDB::openvdb)
globular_test(frame_stats_test SOURCES frame_stats_test.cpp LIBS globular_sim)
