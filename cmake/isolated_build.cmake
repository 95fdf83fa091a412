# One build of some sources for one instruction set, linked into TARGET in isolation
# (README, "One binary for every node"). Compiling the same inline functions (std::vector,
# TBB, our own headers) with different flags breaks the one-definition rule: the linker
# keeps one copy of each, perhaps an AVX-512 one that the scalar path would then call. So
# the build's objects are linked into one relocatable object (ld -r) whose symbols are all
# made local but its table, globular::simd_<PATH>::<TABLE>, with the COMDAT groups dropped
# so that the linker keeps its copies instead of merging them with others'.
#
#   globular_isolated_build(TARGET PATH TABLE STEM SOURCES ... FLAGS ... [LIBS ...])
#
# The sources see GLOBULAR_SIMD_NAMESPACE=simd_<PATH> and define the table in it. The
# isolated object is <STEM>_<PATH>.o in the current binary directory, where
# tests/check_simd_objects.cmake looks for it.
function(globular_isolated_build target path table stem)
    cmake_parse_arguments(BUILD "" "" "SOURCES;FLAGS;LIBS" ${ARGN})
    set(objects ${target}_${stem}_${path})
    add_library(${objects} OBJECT ${BUILD_SOURCES})
    target_compile_definitions(${objects} PRIVATE GLOBULAR_SIMD_NAMESPACE=simd_${path})
    target_compile_options(${objects} PRIVATE ${BUILD_FLAGS})
    target_include_directories(${objects} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
    target_link_libraries(${objects} PRIVATE ${BUILD_LIBS})
    set(isolated ${CMAKE_CURRENT_BINARY_DIR}/${stem}_${path}.o)
    add_custom_command(
        OUTPUT ${isolated}
        COMMAND ${CMAKE_LINKER} -r -o ${isolated}.all $<TARGET_OBJECTS:${objects}>
        COMMAND ${CMAKE_OBJCOPY} --remove-section=.group --wildcard
                --keep-global-symbol=_ZN8globular*simd_${path}*${table}* ${isolated}.all
                ${isolated}
        DEPENDS ${objects} $<TARGET_OBJECTS:${objects}>
        COMMENT "Isolating the ${path} build of ${table}"
        COMMAND_EXPAND_LISTS VERBATIM)
    target_sources(${target} PRIVATE ${isolated})
endfunction()
