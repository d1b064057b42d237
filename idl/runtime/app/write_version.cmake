# Writes OUT (a header defining SWA_VERSION as "VERSION+<commit>[-dirty]") from the checkout at SOURCE_DIR, and
# only when the text changed, so a build after a commit records the new commit and a build without one recompiles
# nothing. Run at every build by the swa_version target (idl/runtime/app/CMakeLists.txt).
set(commit "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  # --exclude=*: no tag names, the commit alone; --dirty: uncommitted changes to tracked files are not that commit.
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12 --exclude=*
                  WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE described RESULT_VARIABLE status
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(status EQUAL 0 AND described)
    set(commit ${described})
  endif()
endif()
set(text "#pragma once\n// Generated at build time by idl/runtime/app/write_version.cmake.\n#define SWA_VERSION \"${VERSION}+${commit}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
