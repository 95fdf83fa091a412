# Tests of globular_surface.
globular_test(surface_tests
    SOURCES surface_kernel_test.cpp
            surface_settings_test.cpp
            surface_mesh_test.cpp
    LIBS globular_surface)
