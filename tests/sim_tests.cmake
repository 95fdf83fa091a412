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
globular_test(simd_path_test SOURCES simd_path_test.cpp LIBS globular_sim)
globular_test(cell_schedule_test SOURCES cell_schedule_test.cpp LIBS globular_sim)
globular_test(left_pack_test SOURCES left_pack_test.cpp left_pack_probe.cpp LIBS globular_sim)
set_source_files_properties(left_pack_probe.cpp PROPERTIES COMPILE_OPTIONS "-mavx2;-mfma")
target_include_directories(left_pack_test PRIVATE ${PROJECT_SOURCE_DIR}/sim)

add_test(NAME SimdPath.ObjectsAreIsolatedAndBuiltForTheirPath
         COMMAND ${CMAKE_COMMAND} -DOBJECTS=${PROJECT_BINARY_DIR}/sim -DSTEM=force_kernels
                 -DTABLE=kForceKernels -DPATHS=scalar,avx2,avx512 -DNM=${CMAKE_NM}
                 -DOBJDUMP=${CMAKE_OBJDUMP} -P ${CMAKE_CURRENT_SOURCE_DIR}/check_simd_objects.cmake)

# The physics and thermal suites again on each build of the force loops (simd_path.h);
# a path this CPU lacks is reported as skipped.
foreach(path scalar avx2 avx512)
    foreach(suite physics_test thermal_test)
        add_test(NAME ${suite}.simd_${path} COMMAND ${suite})
        set_tests_properties(${suite}.simd_${path} PROPERTIES
            ENVIRONMENT GLOBULAR_SIMD=${path} SKIP_REGULAR_EXPRESSION "this CPU lacks"
            TIMEOUT 600)
    endforeach()
endforeach()
globular_test(stable_step_test SOURCES stable_step_test.cpp LIBS globular_sim)
