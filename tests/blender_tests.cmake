# The Blender add-on (blender/) on a tiny run, headless (issue 16); skipped when Blender
# is absent (WITH_BLENDER=1 scripts/setup.sh installs it). ctest -L blender runs it alone.
add_test(NAME Blender.ImportsAndRendersAnOutputFolder
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/blender_test.sh $<TARGET_FILE:globular>
                 ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/blender_test
                 ${PROJECT_BINARY_DIR}/io_import_globular.zip)
set_tests_properties(Blender.ImportsAndRendersAnOutputFolder PROPERTIES
    LABELS blender SKIP_RETURN_CODE 77 TIMEOUT 120)
# The add-on's PLY reader under plain python3 (no Blender): formats, polygons, truncation.
find_program(GLOBULAR_PYTHON3 python3)
if(GLOBULAR_PYTHON3)
    add_test(NAME Blender.PlyReaderReadsEveryFormat
             COMMAND ${GLOBULAR_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/blender_ply_test.py)
    set_tests_properties(Blender.PlyReaderReadsEveryFormat PROPERTIES LABELS blender TIMEOUT 60)
endif()
