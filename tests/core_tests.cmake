# Tests of globular_core.
globular_test(settings_schema_test SOURCES settings_schema_test.cpp LIBS globular_core)

# The one-way rule of the layout: no file includes a header of a layer above its own.
add_test(NAME Layout.IncludesGoDownTheLayers
         COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -P
                 ${CMAKE_CURRENT_SOURCE_DIR}/check_layers.cmake)
# ... and the check catches a core header that includes a simulation header.
add_test(NAME Layout.CheckCatchesAnUpwardInclude
         COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_CURRENT_SOURCE_DIR}/data/layering -P
                 ${CMAKE_CURRENT_SOURCE_DIR}/check_layers.cmake)
set_tests_properties(Layout.CheckCatchesAnUpwardInclude PROPERTIES PASS_REGULAR_EXPRESSION
    "core/clock.h \\(layer core\\) includes step.h of the layer above")
