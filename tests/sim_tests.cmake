# Tests of globular_sim.
globular_test(globule_cache_test SOURCES globule_cache_test.cpp LIBS globular_sim OpenVDB::openvdb)
globular_test(frame_stats_test SOURCES frame_stats_test.cpp LIBS globular_sim)
globular_test(physics_test
    SOURCES pair_force_test.cpp forces_test.cpp integrator_test.cpp emitter_test.cpp
            simulation_test.cpp collider_test.cpp rigid_body_test.cpp collider_poses_test.cpp
            material_pair_test.cpp
    LIBS globular_sim)
globular_test(mesh_sdf_test SOURCES mesh_sdf_test.cpp LIBS globular_sim)
globular_test(thermal_test SOURCES thermal_test.cpp LIBS globular_sim)
