# The one-way rule of the layout (README, Layout): a file may include headers of its own
# layer and of the layers below it, never of a layer above.
#
#   core <- sim <- surface <- render <- cli <- paper <- cli/main.cpp (the command)
#
# Run by ctest:  cmake -DROOT=<source dir> -P tests/check_layers.cmake
# Headers are included by bare name ("errors.h"), so each name is looked up in the layer
# folders; generated and system headers belong to no layer and are not checked.

if(NOT ROOT)
    message(FATAL_ERROR "check_layers: pass -DROOT=<source dir>")
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)
set(layers core sim surface render cli paper)
set(command_file "cli/main.cpp")

set(index 0)
foreach(layer IN LISTS layers)
    file(GLOB headers RELATIVE "${ROOT}/${layer}" "${ROOT}/${layer}/*.h")
    foreach(header IN LISTS headers)
        if(DEFINED "layer_of_${header}")
            message(SEND_ERROR "check_layers: ${header} exists in two layers")
        endif()
        set("layer_of_${header}" ${index})
    endforeach()
    math(EXPR index "${index} + 1")
endforeach()
list(LENGTH layers top)

set(violations 0)
set(index 0)
foreach(layer IN LISTS layers)
    file(GLOB sources RELATIVE "${ROOT}" "${ROOT}/${layer}/*.h" "${ROOT}/${layer}/*.cpp")
    foreach(source IN LISTS sources)
        set(own ${index})
        if(source STREQUAL command_file)
            set(own ${top})
        endif()
        file(STRINGS "${ROOT}/${source}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
        foreach(line IN LISTS includes)
            string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" header "${line}")
            get_filename_component(header "${header}" NAME)
            if(NOT DEFINED "layer_of_${header}")
                continue()
            endif()
            set(theirs "${layer_of_${header}}")
            if(theirs GREATER own)
                list(GET layers ${theirs} above)
                message(SEND_ERROR "check_layers: ${source} (layer ${layer}) includes "
                                   "${header} of the layer above, ${above}")
                math(EXPR violations "${violations} + 1")
            endif()
        endforeach()
    endforeach()
    math(EXPR index "${index} + 1")
endforeach()

if(violations GREATER 0)
    message(FATAL_ERROR "check_layers: ${violations} include(s) break the one-way rule")
endif()
message(STATUS "check_layers: every include goes down the layers")
