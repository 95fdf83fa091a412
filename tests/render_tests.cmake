# Tests of globular_render. render_unit_tests need no OpenGL; renderer_tests and
# render_stage_tests draw through OSMesa (llvmpipe) and compare pixels and goldens
# (tests/data/render; GLOBULAR_UPDATE_GOLDENS=1 rewrites them, see docs/render.md).
globular_test(render_unit_tests
    SOURCES render_settings_test.cpp
            png_image_test.cpp
            color_ramp_test.cpp
            camera_test.cpp
            scene_extent_test.cpp
            contact_sheet_test.cpp
            sphere_culling_test.cpp
            tone_map_test.cpp
            environment_test.cpp
            ground_shadow_region_test.cpp
            occlusion_region_test.cpp
    LIBS globular_render OpenEXR::OpenEXR Imath::Imath)
globular_test(renderer_tests
    SOURCES renderer_test.cpp
            render_golden_test.cpp
            render_output_test.cpp
            liquid_render_test.cpp
            motion_blur_test.cpp
            lighting_test.cpp
            gl_backend_test.cpp
    LIBS globular_render OpenEXR::OpenEXR Imath::Imath)
globular_test(render_stage_tests
    SOURCES render_stage_test.cpp
    LIBS globular_render)
# Issue 17: a split render draws one run's pixels (the render plan).
globular_test(render_plan_tests
    SOURCES render_plan_test.cpp
    LIBS globular_render)
