# Tests of globular_sim.
globular_test(globule_cache_test SOURCES globule_cache_test.cpp LIBS globular_sim OpenVDB::openvdb)
