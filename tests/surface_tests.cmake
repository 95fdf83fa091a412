# Tests of globular_surface. surface_tests stays OpenVDB-free (fast to compile);
# surface_vdb_tests includes OpenVDB to inspect grids and files (and the leaf masks' Coord).
globular_test(surface_tests
    SOURCES surface_kernel_test.cpp
            surface_settings_test.cpp
            surface_mesh_test.cpp
            surface_frame_test.cpp
            surface_stage_test.cpp
            splat_kernel_test.cpp
    LIBS globular_surface)
# The splat loop's builds (surface/splat_kernel.h) are isolated like the force loops'.
add_test(NAME SplatKernel.ObjectsAreIsolatedAndBuiltForTheirPath
         COMMAND ${CMAKE_COMMAND} -DOBJECTS=${PROJECT_BINARY_DIR}/surface -DSTEM=splat_kernel
                 -DTABLE=kSplatKernels -DPATHS=scalar,avx2,avx512 -DNM=${CMAKE_NM}
                 -DOBJDUMP=${CMAKE_OBJDUMP} -P ${CMAKE_CURRENT_SOURCE_DIR}/check_simd_objects.cmake)
globular_test(surface_vdb_tests
    SOURCES surface_vdb_test.cpp
            leaf_masks_test.cpp
    LIBS globular_surface OpenVDB::openvdb)
# Cutting colliders out of the liquid (collider_cut.h); includes OpenVDB to read the grids.
globular_test(collider_cut_tests
    SOURCES collider_cut_test.cpp
    LIBS globular_surface OpenVDB::openvdb)
# Damaged and hostile input files: every reader returns or names the file (issue 11).
globular_test(damaged_files_test
    SOURCES damaged_files_test.cpp
    LIBS globular_surface OpenVDB::openvdb)
# Temperature out of the surface stage: the grid and the mesh's per-vertex attributes.
globular_test(surface_temperature_tests
    SOURCES surface_temperature_test.cpp
    LIBS globular_surface OpenVDB::openvdb)
# Velocity out of the surface stage: the "vel" grid and the mesh's vx vy vz (issue 16).
globular_test(surface_velocity_tests
    SOURCES surface_velocity_test.cpp
    LIBS globular_surface OpenVDB::openvdb)
