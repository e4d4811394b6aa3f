# How this build was made, recorded in every run.json ("build"): the source's
# git commit, the compiler, the build type and the flags. Taken when CMake
# configures, into a small generated header that is rewritten only when its
# text changes (configure_file), so a configure with nothing new rebuilds
# nothing; a new commit or checkout makes the next `cmake --build` configure
# again (below), and so rebuilds one file.
# Included from the top CMakeLists.txt after sphclip_options is defined.

set(sphclip_git_commit "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
    # Only the source's own repository: a source tree unpacked inside some
    # other clone must not record that clone's commit.
    execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --show-toplevel
        WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
        OUTPUT_VARIABLE sphclip_git_top RESULT_VARIABLE sphclip_git_rc
        OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(sphclip_git_rc EQUAL 0)
        file(REAL_PATH "${sphclip_git_top}" sphclip_git_top)
        file(REAL_PATH "${PROJECT_SOURCE_DIR}" sphclip_source_real)
    endif()
    if(sphclip_git_rc EQUAL 0 AND sphclip_git_top STREQUAL sphclip_source_real)
        execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
            WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
            OUTPUT_VARIABLE sphclip_git_describe RESULT_VARIABLE sphclip_git_rc
            OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
        if(sphclip_git_rc EQUAL 0 AND sphclip_git_describe)
            set(sphclip_git_commit "${sphclip_git_describe}")
        endif()
        # A commit or a checkout configures again at the next build, so the
        # commit recorded is the one built: HEAD, and the branch it names
        # (a packed ref has no file; packed-refs then stands for it). Edits
        # that make the tree dirty are seen at the next configure only.
        execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --git-path HEAD
            WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
            OUTPUT_VARIABLE sphclip_git_head OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
        execute_process(COMMAND ${GIT_EXECUTABLE} symbolic-ref -q HEAD
            WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
            OUTPUT_VARIABLE sphclip_git_branch OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
        set(sphclip_git_watch ${sphclip_git_head})
        foreach(ref ${sphclip_git_branch} packed-refs)
            execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --git-path ${ref}
                WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                OUTPUT_VARIABLE sphclip_git_ref OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
            list(APPEND sphclip_git_watch ${sphclip_git_ref})
        endforeach()
        foreach(watched ${sphclip_git_watch})
            if(NOT IS_ABSOLUTE "${watched}")
                set(watched "${PROJECT_SOURCE_DIR}/${watched}")
            endif()
            if(EXISTS "${watched}")
                set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY
                    CMAKE_CONFIGURE_DEPENDS "${watched}")
            endif()
        endforeach()
    endif()
endif()

# The flags every sphclip source is compiled with: CMake's own for the build
# type, then sphclip_options' (warnings, -march, the sanitizers); -Werror is
# behind a generator expression there, so it is added by hand.
if(CMAKE_BUILD_TYPE)
    string(TOUPPER "${CMAKE_BUILD_TYPE}" sphclip_build_type_upper)
    set(sphclip_type_flags "${CMAKE_CXX_FLAGS_${sphclip_build_type_upper}}")
endif()
get_target_property(sphclip_option_flags sphclip_options INTERFACE_COMPILE_OPTIONS)
string(GENEX_STRIP "${sphclip_option_flags}" sphclip_option_flags)
if(SPHCLIP_WERROR)
    list(APPEND sphclip_option_flags -Werror)
endif()
list(JOIN sphclip_option_flags " " sphclip_option_flags)
set(sphclip_flags "${CMAKE_CXX_FLAGS} ${sphclip_type_flags} ${sphclip_option_flags}")
string(REGEX REPLACE " +" " " sphclip_flags "${sphclip_flags}")
string(STRIP "${sphclip_flags}" sphclip_flags)

# As C++ string literals.
function(sphclip_c_string variable value)
    string(REPLACE "\\" "\\\\" value "${value}")
    string(REPLACE "\"" "\\\"" value "${value}")
    set(${variable} "\"${value}\"" PARENT_SCOPE)
endfunction()
sphclip_c_string(SPHCLIP_BUILD_GIT_COMMIT "${sphclip_git_commit}")
sphclip_c_string(SPHCLIP_BUILD_COMPILER_ID "${CMAKE_CXX_COMPILER_ID}")
sphclip_c_string(SPHCLIP_BUILD_COMPILER_VERSION "${CMAKE_CXX_COMPILER_VERSION}")
sphclip_c_string(SPHCLIP_BUILD_TYPE_TEXT "${CMAKE_BUILD_TYPE}")
sphclip_c_string(SPHCLIP_BUILD_FLAGS "${sphclip_flags}")
sphclip_c_string(SPHCLIP_BUILD_ARCH "${SPHCLIP_ARCH}")
set(SPHCLIP_BUILD_INFO_DIR ${PROJECT_BINARY_DIR}/generated/build_info)
configure_file(${CMAKE_CURRENT_LIST_DIR}/build_info.hpp.in
    ${SPHCLIP_BUILD_INFO_DIR}/sphclip_build_info.hpp @ONLY)
